// The learning environments' tasks: track's reference is a smooth trajectory whose velocity and
// acceleration are its derivatives and which a simple tracker can follow; navigate's ranges are
// what MuJoCo's own ray sees, its endpoints are free and apart, and a straight flight arrives;
// reset's options set the start and the target, and are refused before anything changes;
// the velocity action reaches the velocity it asks for.
#include <doctest/doctest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "control/position_control.h"
#include "envs/env_batch.h"
#include "geometry/collision_world.h"
#include "perception/depth_camera.h"
#include "planning/rrt_star.h"
#include "vehicle/model_names.h"

namespace aerobox {
namespace {

// One world of `params`, with buffers for its steps.
struct One {
  explicit One(const EnvParams& p) : params(p), batch(p, 1, 1) {
    obs.resize(static_cast<size_t>(batch.observation_size()));
  }
  EnvWorld& world() { return batch.world(0); }
  void Reset(std::uint64_t seed, const EnvOptions& options = {}) {
    batch.Reset({seed}, obs.data(), options);
  }
  EnvStep Step(const std::array<double, 4>& a) { return world().Step(a.data(), obs.data()); }
  // The observation component named `name`.
  float Get(const std::string& name) const {
    const std::vector<std::string> names = params.ObservationNames();
    const auto at = std::find(names.begin(), names.end(), name);
    REQUIRE(at != names.end());
    return obs[static_cast<size_t>(at - names.begin())];
  }
  EnvParams params;
  EnvBatch batch;
  std::vector<float> obs;
};

double Clamp(double x) { return std::clamp(x, -1.0, 1.0); }

// A velocity action flying towards `to` along `feed` [m/s]: feed-forward plus 2/s of the error.
std::array<double, 4> Towards(const EnvParams& p, const Vec3& error, const Vec3& feed) {
  const Vec3 v = (feed - 2.0 * error) / p.max_speed;
  return {Clamp(v.x()), Clamp(v.y()), Clamp(v.z()), 0.0};
}

EnvParams Track(const std::string& shape) {
  EnvParams p;
  p.task = "track";
  p.track_shape = shape;
  p.action = "velocity";
  p.start_radius = 0.0;
  p.start_speed = 0.0;
  p.start_tilt = 0.0;
  p.start_rate = 0.0;
  return p;
}

TEST_CASE("track: the reference's velocity and acceleration are its derivatives") {
  for (const char* shape : {"circle", "figure8"}) {
    CAPTURE(shape);
    One env(Track(shape));
    for (std::uint64_t seed = 0; seed < 5; ++seed) {
      env.Reset(seed);
      const EnvTask& task = env.world().task();
      const double h = 1e-4, t = 0.37;
      const Vec3 v = (task.Reference(t + h) - task.Reference(t - h)) / (2 * h);
      const Vec3 a =
          (task.Reference(t + h) - 2 * task.Reference(t) + task.Reference(t - h)) / (h * h);
      // the task's components: the reference's velocity and acceleration now, then 3 samples
      std::vector<float> extra(static_cast<size_t>(6 + 9 * env.params.track_points));
      const State s = env.world().state();
      task.Observe(t, s, extra.data());
      const float* now = extra.data();
      for (int i = 0; i < 3; ++i) {
        CHECK(now[i] == doctest::Approx(v[i]).epsilon(1e-4));
        CHECK(now[3 + i] == doctest::Approx(a[i]).epsilon(1e-3).scale(1.0));
        // the second sample ahead: its position minus the vehicle's
        CHECK(extra[15 + i] ==
              doctest::Approx(task.Reference(t + 2 * 0.1)[i] - s.p_W[i]).epsilon(1e-5));
      }
      double fastest = 0.0;  // over a whole period at most 2 pi / 0.25 s
      for (double u = 0.0; u < 30.0; u += 0.01) {
        fastest =
            std::max(fastest, (task.Reference(u + h) - task.Reference(u - h)).norm() / (2 * h));
        CHECK(std::abs(task.Reference(u).z() - env.params.target.z()) < 1e-12);
        CHECK((task.Reference(u) - env.params.target).head<2>().norm() <= 1.0 + 1e-9);
      }
      CHECK(fastest <= env.params.track_speed + 1e-6);
      CHECK(fastest >= 0.5 * env.params.track_speed - 1e-6);
    }
  }
}

// The cascade's outer loops (control/position_control.h) driving the ctatt action: a scripted
// policy from the observation alone (the reference is p - d, its velocity and acceleration the
// observation's), turned into the action by the scaling the docs give.
class CascadePolicy {
 public:
  explicit CascadePolicy(const EnvParams& p)
      : params_(p), vehicle_(p.Vehicle()), loop_(PositionControlParams(), vehicle_.mass) {}

  std::array<double, 4> operator()(One& env) {
    const Vec3 p = env.world().seen().p_W, v = env.world().seen().v_W;
    PositionSetpoint setpoint;
    setpoint.p_W = p - Vec3(env.Get("dx"), env.Get("dy"), env.Get("dz"));
    setpoint.v_W = Vec3(env.Get("ref_vx"), env.Get("ref_vy"), env.Get("ref_vz"));
    setpoint.a_W = Vec3(env.Get("ref_ax"), env.Get("ref_ay"), env.Get("ref_az"));
    AttitudeSetpoint out;
    REQUIRE(loop_.Update(setpoint, p, v, env.world().seen().q_WB, 0.01, &out));
    const Mat3 R = out.q_WB.toRotationMatrix();  // R_z(yaw) R_y(pitch) R_x(roll)
    const double low = vehicle_.MinRotorThrust(), high = vehicle_.MaxRotorThrust();
    return {Clamp(2.0 * (out.thrust / 4.0 - low) / (high - low) - 1.0),
            Clamp(std::atan2(R(2, 1), R(2, 2)) / params_.max_tilt),
            Clamp(std::asin(-R(2, 0)) / params_.max_tilt),
            Clamp(std::atan2(R(1, 0), R(0, 0)) / 3.14159265358979323846)};
  }

 private:
  EnvParams params_;
  QuadParams vehicle_;
  PositionController loop_;
};

TEST_CASE("track: the cascade driving the attitude action follows the reference within 5 cm") {
  EnvParams params = Track("both");
  params.action = "ctatt";
  One env(params);
  for (std::uint64_t seed = 0; seed < 6; ++seed) {
    CAPTURE(seed);
    env.Reset(seed);
    CascadePolicy policy(params);
    std::vector<double> errors;
    EnvStep step;
    while (!step.terminated && !step.truncated) {
      step = env.Step(policy(env));
      errors.push_back(Vec3(env.Get("dx"), env.Get("dy"), env.Get("dz")).norm());
    }
    CHECK(step.truncated);
    const double late = *std::max_element(errors.begin() + errors.size() / 2, errors.end());
    CHECK(late < 0.05);
  }
  // and a random policy does not follow it
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> any(-1.0, 1.0);
  env.Reset(9);
  EnvStep step;
  while (!step.terminated && !step.truncated) step = env.Step({any(rng), any(rng), any(rng), 0});
  CHECK(step.terminated);
}

EnvParams Navigate() {
  EnvParams p;
  p.task = "navigate";
  p.action = "velocity";
  p.start_speed = 0.0;
  p.start_tilt = 0.0;
  p.start_rate = 0.0;
  return p;
}

TEST_CASE("navigate: the ranges are what MuJoCo's ray sees, capped by the bounds and the reach") {
  One env(Navigate());
  const Simulation& sim = env.batch.Showing(0);
  const Aabb bounds = env.batch.map().bounds;
  const int vehicle = mj_name2id(sim.model(), mjOBJ_BODY, model_names::kBody);
  REQUIRE(vehicle >= 0);
  int hits = 0;
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    env.Reset(seed);
    const Vec3 p = env.world().state().p_W;
    for (int k = 0; k < env.params.range_rays + 2; ++k) {
      Vec3 d = k == env.params.range_rays ? Vec3(-Vec3::UnitZ()) : Vec3(Vec3::UnitZ());
      if (k < env.params.range_rays) {
        const double angle = 2.0 * 3.14159265358979323846 * k / env.params.range_rays;
        d = Vec3(std::cos(angle), std::sin(angle), 0.0);
      }
      int geom = -1;
      const double mj =
          mj_ray(sim.model(), sim.data(), p.data(), d.data(), nullptr, 1, vehicle, &geom);
      double exit = env.params.range_max;  // the bounds, which MuJoCo's scene has no walls for
      for (int i = 0; i < 3; ++i) {
        if (d[i] > 0) exit = std::min(exit, (bounds.max[i] - p[i]) / d[i]);
        if (d[i] < 0) exit = std::min(exit, (bounds.min[i] - p[i]) / d[i]);
      }
      const double expected = mj >= 0 ? std::min(mj, exit) : exit;
      const std::string name = k < env.params.range_rays    ? "range" + std::to_string(k)
                               : k == env.params.range_rays ? "range_down"
                                                            : "range_up";
      CHECK(env.Get(name) == doctest::Approx(expected).epsilon(1e-5));
      hits += mj >= 0 && mj < exit;
    }
  }
  CHECK(hits > 20);  // trees and the floor were seen, not only the reach
}

TEST_CASE("navigate: the depth image is what MuJoCo's ray sees along each pixel, within reach") {
  EnvParams params = Navigate();
  params.depth_width = 16;
  params.depth_height = 12;
  One env(params);
  const Simulation& sim = env.batch.Showing(0);
  const int vehicle = mj_name2id(sim.model(), mjOBJ_BODY, model_names::kBody);
  const int floor_geom = mj_name2id(sim.model(), mjOBJ_GEOM, model_names::kFloorGeom);
  DepthCameraParams camera;  // the observation's camera: the defaults, at 16 x 12 px
  camera.width = 16;
  camera.height = 12;
  camera.range = params.range_max;
  const std::vector<std::string> names = params.ObservationNames();
  REQUIRE(names.back() == "depth_11_15");
  REQUIRE(env.batch.observation_size() == static_cast<int>(names.size()));
  int trees = 0;
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    env.Reset(seed);
    // the pose and rays of the camera on the vehicle as it is (the image itself is not used)
    const DepthImage frame = DepthCamera(camera, 1).Capture(env.world().state(), {}, Aabb());
    for (int v = 0; v < 12; ++v) {
      for (int u = 0; u < 16; ++u) {
        const Vec3 d = frame.R_WC * frame.RayC(u, v);
        int geom = -1;
        const mjtByte groups[mjNGROUP] = {1, 1, 0, 0, 0, 0};
        const double mj = mj_ray(sim.model(), sim.data(), frame.origin_W.data(), d.data(), groups,
                                 1, vehicle, &geom);
        const float depth = env.Get("depth_" + std::to_string(v) + "_" + std::to_string(u));
        CHECK(depth > 0.0f);
        CHECK(depth <= params.range_max + 1e-5);
        if (mj < 0 || mj > params.range_max || geom == floor_geom) continue;
        CHECK(depth == doctest::Approx(mj * frame.RayC(u, v).z()).epsilon(1e-4));
        ++trees;
      }
    }
  }
  CHECK(trees > 50);
}

TEST_CASE("navigate: free endpoints apart, arrival by a straight flight, a tree is a crash") {
  EnvParams params = Navigate();
  params.forest_trees = 0;
  One empty(params);
  params.forest_trees = 30;
  const Map forest = FindEnvTask("navigate").map(params);
  CollisionParams collision;
  collision.vehicle_size = params.Vehicle().collision_size;
  collision.clearance = 0.2;
  const CollisionWorld world(forest, collision);
  One trees(params);
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    trees.Reset(seed);
    const Vec3 start = trees.world().state().p_W;
    const Vec3 goal = trees.world().task().Reference(0.0);
    CHECK(world.IsPointFree(start));
    CHECK(world.IsPointFree(goal));
    CHECK((goal - start).norm() >= params.goal_distance);
  }
  empty.Reset(7);
  const double first = (empty.world().state().p_W - empty.world().task().Reference(0)).norm();
  double progress = 0.0;
  EnvStep step;
  while (!step.terminated && !step.truncated) {
    const Vec3 d(empty.Get("dx"), empty.Get("dy"), empty.Get("dz"));
    step = empty.Step(Towards(empty.params, d, Vec3::Zero()));
    progress += step.terms[1];
  }
  CHECK(step.terminated);
  CHECK(step.terms[5] == params.reward_arrival);  // arrived
  const double last = (empty.world().state().p_W - empty.world().task().Reference(0)).norm();
  CHECK(last < params.arrival_radius);
  CHECK(progress == doctest::Approx(params.reward_progress * (first - last)));
  // straight at the goal through the trees: some flight meets a trunk and ends there
  int crashes = 0;
  for (std::uint64_t seed = 0; seed < 10; ++seed) {
    trees.Reset(seed);
    EnvStep s;
    while (!s.terminated && !s.truncated) {
      const Vec3 d(trees.Get("dx"), trees.Get("dy"), trees.Get("dz"));
      s = trees.Step(Towards(trees.params, d, Vec3::Zero()));
    }
    crashes += s.terminated && s.terms[5] == 0.0;
  }
  CHECK(crashes >= 1);
}

TEST_CASE("navigate: a planned path flown with the velocity action arrives through the trees") {
  // the scripted policy: aerobox's RRT* through the forest (the same clearance as the draws),
  // then pure pursuit along the path at 1 m/s with the velocity action
  EnvParams params = Navigate();
  One env(params);
  CollisionParams collision;
  collision.vehicle_size = params.Vehicle().collision_size;
  collision.clearance = 0.15;
  const CollisionWorld world(env.batch.map(), collision);
  const Validity validity{[&](const Vec3& p) { return world.IsPointFree(p); },
                          [&](const Vec3& a, const Vec3& b) { return world.IsSegmentFree(a, b); }};
  RrtStarParams rrt;
  rrt.time_budget = 100.0;
  rrt.max_iterations = 2000;
  rrt.max_search_iterations = 100000;
  int arrived = 0;
  for (std::uint64_t seed = 0; seed < 5; ++seed) {
    CAPTURE(seed);
    env.Reset(seed);
    const Vec3 goal = env.world().task().Reference(0.0);
    const PlanResult plan =
        PlanRrtStar(env.world().state().p_W, goal, world.free_bounds(), validity, rrt);
    REQUIRE(plan.status == PlanStatus::kSolved);
    size_t next = 1;
    EnvStep step;
    while (!step.terminated && !step.truncated) {
      const Vec3 p = env.world().seen().p_W;
      while (next + 1 < plan.path.size() && (plan.path[next] - p).norm() < 0.3) ++next;
      const Vec3 to = plan.path[next] - p;
      const Vec3 v = to.norm() > 1e-9 ? to.normalized() * std::min(1.0, 2.0 * to.norm()) : to;
      step = env.Step({Clamp(v.x() / params.max_speed), Clamp(v.y() / params.max_speed),
                       Clamp(v.z() / params.max_speed), 0.0});
    }
    CHECK(step.terminated);
    arrived += step.terms[5] == params.reward_arrival;
  }
  CHECK(arrived == 5);
  // a random policy does not arrive
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> any(-1.0, 1.0);
  for (std::uint64_t seed = 0; seed < 5; ++seed) {
    env.Reset(seed);
    EnvStep step;
    while (!step.terminated && !step.truncated) {
      step = env.Step({any(rng), any(rng), any(rng), any(rng)});
    }
    CHECK(step.terms[5] == 0.0);
  }
}

TEST_CASE("reset's options set the start and the target, and bad ones change nothing") {
  EnvParams hover;
  One env(hover);
  EnvOptions options;
  options.start = Vec3(0.5, -0.5, 1.0);
  options.target = Vec3(1, 1, 2);
  env.Reset(4, options);
  CHECK(env.world().state().p_W.isApprox(Vec3(0.5, -0.5, 1.0)));
  CHECK(env.Get("dx") == doctest::Approx(-0.5));
  CHECK(env.Get("dz") == doctest::Approx(-1.0));
  const Vec3 before = env.world().state().p_W;
  EnvOptions below;
  below.start = Vec3(0, 0, -1);
  CHECK_THROWS_WITH_AS(env.Reset(5, below), doctest::Contains("options[\"start\"] [0, 0, -1]"),
                       std::invalid_argument);
  CHECK(env.world().state().p_W == before);
  One nav(Navigate());
  const Box& tree = nav.batch.map().boxes.front();
  EnvOptions inside;
  inside.target = tree.extent.Center();
  CHECK_THROWS_WITH_AS(nav.Reset(1, inside), doctest::Contains("is not free"),
                       std::invalid_argument);
}

TEST_CASE("the velocity action reaches the velocity it asks for, and bad maps are named") {
  EnvParams p;
  p.action = "velocity";
  p.start_radius = 0.0;
  p.start_speed = 0.0;
  p.start_tilt = 0.0;
  p.start_rate = 0.0;
  One env(p);
  env.Reset(1);
  for (int i = 0; i < 300; ++i) env.Step({0.25, -0.25, 0.0, 0.0});        // 3 s of 0.5, -0.5 m/s
  CHECK((env.world().state().v_W - Vec3(0.5, -0.5, 0.0)).norm() < 0.03);  // the PID's tail
  EnvParams bad = Navigate();
  bad.map = "no/such/map.json";
  CHECK_THROWS_WITH_AS(EnvBatch(bad, 1, 1), doctest::Contains("map 'no/such/map.json'"),
                       std::invalid_argument);
  bad = Navigate();
  bad.goal_distance = 50;
  CHECK_THROWS_WITH_AS(EnvBatch(bad, 1, 1), doctest::Contains("no free start and goal 50 m"),
                       std::invalid_argument);
}

TEST_CASE("domain randomisation: each episode's vehicle and wind within their ranges, by seed") {
  EnvParams params = Track("both");
  params.action = "ctatt";
  params.vary_mass = params.vary_inertia = params.vary_thrust = 0.2;
  params.vary_yaw_moment = params.vary_motor_lag = params.vary_rotor_limit = 0.2;
  params.wind_speed = 3.0;
  params.wind_turbulence = 0.5;
  params.sensors = true;
  params.vary_sensor_noise = 0.5;
  One env(params), again(params);
  const QuadParams nominal = params.Vehicle();
  const int body = mj_name2id(env.batch.Showing(0).model(), mjOBJ_BODY, model_names::kBody);
  std::vector<double> masses;
  for (std::uint64_t seed = 0; seed < 8; ++seed) {
    CAPTURE(seed);
    env.Reset(seed);
    const mjModel* m = env.batch.Showing(0).model();
    masses.push_back(m->body_mass[body]);
    CHECK(std::abs(masses.back() / nominal.mass - 1.0) <= 0.2 + 1e-12);
    for (int i = 0; i < m->nu; ++i) {
      CHECK(std::abs(m->actuator_gainprm[mjNGAIN * i] - 1.0) <= 0.2 + 1e-12);
      CHECK(std::abs(m->actuator_dynprm[mjNDYN * i] / nominal.motor_time_constant - 1.0) <=
            0.2 + 1e-12);
    }
    const Vec3 wind = env.world().vehicle_world().air().wind();
    CHECK(wind.head<2>().norm() < 3.0 + 4 * 0.5);  // the mean and the turbulence
    // the observation is the estimate: near the truth (the filter starts within its prior's
    // few centimetres), not it
    const Vec3 seen = env.world().seen().p_W, truth = env.world().state().p_W;
    CHECK((seen - truth).norm() < 0.05);
    CHECK((seen - truth).norm() > 0.0);
    // the same seed draws the same episode; the cascade flies it on the estimate
    again.Reset(seed);
    CHECK(again.batch.Showing(0).model()->body_mass[body] == masses.back());
    CascadePolicy policy(params);
    EnvStep step;
    std::vector<double> errors;
    while (!step.terminated && !step.truncated) {
      step = env.Step(policy(env));
      errors.push_back(
          (env.world().state().p_W - env.world().task().Reference(env.world().time())).norm());
    }
    CHECK(step.truncated);
    CHECK(*std::max_element(errors.begin() + errors.size() / 2, errors.end()) < 0.15);
  }
  CHECK(*std::min_element(masses.begin(), masses.end()) <
        *std::max_element(masses.begin(), masses.end()));
}

TEST_CASE("domain randomisation: one gust per episode, horizontal, up to its peak") {
  EnvParams params;
  params.action = "velocity";  // zero: hold still, so the episodes last
  params.start_speed = params.start_rate = 0.0;
  params.gust_speed = 3.0;
  One env(params);
  int gusty = 0;
  for (std::uint64_t seed = 0; seed < 6; ++seed) {
    env.Reset(seed);
    double strongest = 0.0;
    EnvStep step;
    while (!step.terminated && !step.truncated) {
      step = env.Step({0.0, 0.0, 0.0, 0.0});
      const Vec3 wind = env.world().vehicle_world().air().wind();
      CHECK(wind.z() == 0.0);
      strongest = std::max(strongest, wind.norm());
    }
    CHECK(strongest <= 3.0 + 1e-12);
    CHECK(step.truncated);
    gusty += strongest > 0.1;
  }
  CHECK(gusty >= 4);  // the episodes met their gusts
}

// A user's task, registered from outside src/: hold a point that rises at 0.1 m/s, with the
// height error as one extra observation component.
class Climb : public EnvTask {
 public:
  explicit Climb(const EnvParams& p) : params_(p) {}
  State Begin(EnvRandom& random, const EnvOptions&) override {
    State s;
    s.p_W = params_.target + random.InBall(0.1);
    return s;
  }
  Vec3 Reference(double t) const override { return params_.target + Vec3(0, 0, 0.1 * t); }
  void Observe(double t, const State& s, float* out) const override {
    out[0] = static_cast<float>(s.p_W.z() - Reference(t).z());
  }
  TaskScore Score(double t, const State& s, const double*) override {
    return {{-std::abs(s.p_W.z() - Reference(t).z())}, false};
  }

 private:
  EnvParams params_;
};

TEST_CASE("a user's task is registered by name and flown like the built-in ones") {
  RegisterEnvTask({"climb",
                   [](const EnvParams&) { return std::vector<std::string>{"dz_climb"}; },
                   {"height"},
                   [](const EnvParams& p) {
                     Map room;
                     room.bounds = {p.target - Vec3(3, 3, p.target.z()), p.target + Vec3(3, 3, 3)};
                     return room;
                   },
                   [](const EnvParams& p, const QuadParams&, const Map&) {
                     return std::unique_ptr<EnvTask>(new Climb(p));
                   }});
  EnvParams params;
  params.task = "climb";
  One env(params);
  CHECK(params.ObservationNames().back() == "dz_climb");
  CHECK(params.RewardTermNames() == std::vector<std::string>{"height"});
  env.Reset(2);
  const EnvStep step = env.Step({0, 0, 0, 0});
  REQUIRE(step.terms.size() == 1);
  CHECK(step.reward == step.terms[0]);
  CHECK(env.Get("dz_climb") == doctest::Approx(env.Get("dz")));
  params.task = "climbing";
  CHECK_THROWS_WITH_AS(params.Validate(), doctest::Contains("env.task is not one of climb, hover"),
                       std::invalid_argument);
}

}  // namespace
}  // namespace aerobox

namespace aerobox {
namespace {

// The largest distance [m] between the two backends' vehicles over an episode of `params`
// flown from `seed`, each by its own policy from `make_policy`, and the step each episode ended
// at (1000000: at its time limit).
struct Apart {
  double distance = 0.0;
  int ended_mujoco = -1, ended_rigid = -1;
};
template <typename MakePolicy>
Apart FlyBoth(EnvParams params, std::uint64_t seed, MakePolicy make_policy) {
  auto policy_mujoco = make_policy(), policy_rigid = make_policy();
  params.backend = "mujoco";
  One mujoco(params);
  params.backend = "rigid";
  One rigid(params);
  mujoco.Reset(seed);
  rigid.Reset(seed);
  Apart apart;
  for (int k = 0; apart.ended_mujoco < 0 || apart.ended_rigid < 0; ++k) {
    for (One* env : {&mujoco, &rigid}) {
      int& ended = env == &mujoco ? apart.ended_mujoco : apart.ended_rigid;
      if (ended >= 0) continue;
      const EnvStep step = env->Step(env == &mujoco ? policy_mujoco(*env) : policy_rigid(*env));
      if (step.terminated || step.truncated) ended = step.terminated ? k : 1000000;
    }
    if (apart.ended_mujoco < 0 && apart.ended_rigid < 0) {
      apart.distance =
          std::max(apart.distance, (mujoco.world().state().p_W - rigid.world().state().p_W).norm());
    }
  }
  return apart;
}

}  // namespace

TEST_CASE("the rigid backend flies as MuJoCo: hover and an aggressive track within 1 mm") {
  EnvParams hover;
  hover.action = "ctatt";
  hover.task = "track";
  hover.track_speed = 0.05;  // a reference nearly at rest: hold it, from a random start
  hover.track_size = 0.1;
  hover.start_radius = 1.0;
  for (std::uint64_t seed = 0; seed < 3; ++seed) {
    CAPTURE(seed);
    const Apart a = FlyBoth(hover, seed, [&hover] { return CascadePolicy(hover); });
    CHECK(a.ended_mujoco == 1000000);  // 10 s, to the time limit
    CHECK(a.ended_rigid == 1000000);
    CHECK(a.distance < 1e-6);  // the issue asks 1 mm; rounding alone: below 1e-10 m
  }
  EnvParams track = hover;
  track.track_speed = 3.0;  // [m/s] on a 1.5 m circle or figure-8: about 6 m/s^2
  track.track_size = 1.5;
  track.start_radius = 0.0;
  track.vehicle = "tello";
  for (std::uint64_t seed = 0; seed < 3; ++seed) {
    CAPTURE(seed);
    const Apart a = FlyBoth(track, seed, [&track] { return CascadePolicy(track); });
    CHECK(a.ended_mujoco == 1000000);
    CHECK(a.ended_rigid == 1000000);
    CHECK(a.distance < 1e-6);  // the issue asks 1 mm; rounding alone: below 1e-10 m
  }
}

TEST_CASE("the rigid backend: a trunk or the floor ends the episode at MuJoCo's step") {
  EnvParams params = Navigate();
  int crashes = 0;
  for (std::uint64_t seed = 0; seed < 10; ++seed) {
    CAPTURE(seed);
    // straight at the goal through the trees, then down
    const Apart a = FlyBoth(params, seed, [] {
      return [](One& env) {
        const Vec3 d(env.Get("dx"), env.Get("dy"), env.Get("dz"));
        std::array<double, 4> action = Towards(env.params, d, Vec3::Zero());
        if (env.world().time() > 4.0) action = {0.0, 0.0, -1.0, 0.0};
        return action;
      };
    });
    CHECK(a.ended_mujoco == a.ended_rigid);
    CHECK(a.distance < 1e-6);  // the issue asks 1 mm; rounding alone: below 1e-10 m
    crashes += a.ended_mujoco < 1000000;
  }
  CHECK(crashes >= 5);
}

}  // namespace aerobox
