// The built-in tasks (hover, track, navigate), the task registry and a world's random stream.
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "common/number_format.h"
#include "common/schema.h"
#include "envs/env_task.h"
#include "geometry/collision_world.h"
#include "geometry/ray_cast.h"
#include "map/map_reader.h"
#include "perception/depth_camera.h"

namespace aerobox {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string Point(const Vec3& p) {
  return "[" + FormatNumber(p.x()) + ", " + FormatNumber(p.y()) + ", " + FormatNumber(p.z()) + "]";
}

// A point reset's options give, when given: finite, above the floor.
void CheckPoint(const std::optional<Vec3>& p, const char* name) {
  if (p && (!p->allFinite() || p->z() <= 0.0)) {
    throw std::invalid_argument(std::string("options[\"") + name + "\"] " + Point(*p) +
                                ": expected finite coordinates [m] above the floor (z > 0)");
  }
}

// The terms every task shares after its position term: velocity, body rate and action.
void AddMotionTerms(const EnvParams& p, const Vec3& velocity_error, const State& s,
                    const double* action, std::vector<double>* terms) {
  double squared = 0.0;
  for (int i = 0; i < p.ActionSize(); ++i) squared += action[i] * action[i];
  terms->push_back(-p.reward_velocity * velocity_error.norm());
  terms->push_back(-p.reward_rate * s.w_B.norm());
  terms->push_back(-p.reward_action * squared);
}

// An empty room with a floor around `centre`, reaching `reach` [m] each way.
Map Room(const std::string& name, const Vec3& centre, double reach) {
  Map room;
  room.name = name;
  room.bounds = {Vec3(centre.x() - reach, centre.y() - reach, 0.0),
                 Vec3(centre.x() + reach, centre.y() + reach, centre.z() + reach)};
  return room;
}

// ---- hover: reach and hold the target ----

class HoverTask : public EnvTask {
 public:
  explicit HoverTask(const EnvParams& params) : params_(params) {}

  State Begin(EnvRandom& random, const EnvOptions& options) override {
    target_ = options.target.value_or(params_.target);
    State s;
    s.p_W = target_ + random.InBall(params_.start_radius);
    s.v_W = random.InBall(params_.start_speed);
    random.Attitude(params_, &s);
    if (options.start) s.p_W = *options.start;
    return s;
  }
  Vec3 Reference(double) const override { return target_; }
  void Observe(double, const State&, float*) const override {}
  TaskScore Score(double, const State& s, const double* action) override {
    const double distance = (s.p_W - target_).norm();
    TaskScore score;
    score.ended = !(distance <= params_.bounds_radius);
    score.terms = {params_.reward_alive, -params_.reward_position * distance};
    AddMotionTerms(params_, s.v_W, s, action, &score.terms);
    return score;
  }

 private:
  EnvParams params_;
  Vec3 target_;
};

// ---- track: follow a random circle or figure-8 ----

// A reference point: position [m], velocity [m/s], acceleration [m/s^2], world ENU.
struct RefPoint {
  Vec3 p, v, a;
};

class TrackTask : public EnvTask {
 public:
  explicit TrackTask(const EnvParams& params) : params_(params) {}

  State Begin(EnvRandom& random, const EnvOptions& options) override {
    centre_ = options.target.value_or(params_.target);
    const double pick = random.Uniform();
    figure8_ = params_.track_shape == "figure8" || (params_.track_shape == "both" && pick < 0.5);
    size_ = params_.track_size * random.Uniform(0.5, 1.0);
    const double speed = params_.track_speed * random.Uniform(0.5, 1.0);
    heading_ = random.Uniform(-kPi, kPi);
    phase_ = random.Uniform(0.0, 2.0 * kPi);
    const double direction = random.Uniform() < 0.5 ? -1.0 : 1.0;
    // the top speed: the circle's everywhere, the figure-8's at its crossing (|v| = s w sqrt 2)
    omega_ = direction * speed / (figure8_ ? size_ * std::sqrt(2.0) : size_);
    const RefPoint r = At(0.0);
    State s;
    s.p_W = r.p + random.InBall(params_.start_radius);
    s.v_W = r.v + random.InBall(params_.start_speed);
    random.Attitude(params_, &s);
    if (options.start) s.p_W = *options.start;
    return s;
  }

  Vec3 Reference(double t) const override { return At(t).p; }

  void Observe(double t, const State& s, float* out) const override {
    const RefPoint now = At(t);
    int n = 0;
    const auto put = [&](const Vec3& v) {
      for (int i = 0; i < 3; ++i) out[n++] = static_cast<float>(v[i]);
    };
    put(now.v);
    put(now.a);
    for (int j = 1; j <= params_.track_points; ++j) {
      const RefPoint ahead = At(t + j * params_.track_spacing);
      put(ahead.p - s.p_W);
      put(ahead.v);
      put(ahead.a);
    }
  }

  TaskScore Score(double t, const State& s, const double* action) override {
    const RefPoint r = At(t);
    const double distance = (s.p_W - r.p).norm();
    TaskScore score;
    score.ended = !(distance <= params_.bounds_radius);
    score.terms = {params_.reward_alive, -params_.reward_position * distance};
    AddMotionTerms(params_, s.v_W - r.v, s, action, &score.terms);
    return score;
  }

 private:
  // The shape in its own plane (x along the heading), then turned and moved to the centre.
  RefPoint At(double t) const {
    const double th = omega_ * t + phase_, w = omega_, s = size_;
    Vec3 p, v, a;
    if (figure8_) {  // Gerono's lemniscate: (s sin th, s sin th cos th)
      p = Vec3(s * std::sin(th), 0.5 * s * std::sin(2 * th), 0);
      v = Vec3(s * w * std::cos(th), s * w * std::cos(2 * th), 0);
      a = Vec3(-s * w * w * std::sin(th), -2 * s * w * w * std::sin(2 * th), 0);
    } else {
      p = Vec3(s * std::cos(th), s * std::sin(th), 0);
      v = Vec3(-s * w * std::sin(th), s * w * std::cos(th), 0);
      a = -w * w * p;
    }
    const Mat3 turn = Eigen::AngleAxisd(heading_, Vec3::UnitZ()).toRotationMatrix();
    return {centre_ + turn * p, turn * v, turn * a};
  }

  EnvParams params_;
  Vec3 centre_;
  bool figure8_ = false;
  double size_ = 1.0, omega_ = 1.0, heading_ = 0.0, phase_ = 0.0;
};

std::vector<std::string> TrackNames(const EnvParams& p) {
  std::vector<std::string> names;
  const auto add = [&](const std::string& prefix, const char* what) {
    for (const char* axis : {"x", "y", "z"}) names.push_back(prefix + what + axis);
  };
  add("ref_", "v");
  add("ref_", "a");
  for (int j = 1; j <= p.track_points; ++j) {
    const std::string prefix = "ref" + std::to_string(j) + "_";
    add(prefix, "d");
    add(prefix, "v");
    add(prefix, "a");
  }
  return names;
}

// ---- navigate: reach a goal through a map of boxes ----

// A seeded forest: trunks 0.2 to 0.5 m square, as tall as the forest, anywhere in it.
Map Forest(const EnvParams& p) {
  Map forest;
  forest.name = "forest_" + std::to_string(p.forest_seed);
  forest.bounds = {Vec3::Zero(), Vec3(p.forest_size, p.forest_size, p.forest_height)};
  EnvRandom random;
  random.Seed(static_cast<std::uint64_t>(p.forest_seed));
  for (int i = 0; i < p.forest_trees; ++i) {
    const double side = random.Uniform(0.2, 0.5);
    const Vec3 min(random.Uniform(0.0, p.forest_size - side),
                   random.Uniform(0.0, p.forest_size - side), 0.0);
    forest.boxes.push_back({{min, min + Vec3(side, side, p.forest_height)},
                            Vec3(0.4, 0.3, 0.2),
                            "tree_" + std::to_string(i),
                            0});
  }
  return forest;
}

Map NavigateMap(const EnvParams& p) {
  if (p.map.empty()) return Forest(p);
  try {
    return ReadMapFile(p.map);
  } catch (const std::exception& e) {
    throw std::invalid_argument("map '" + p.map + "': " + e.what());
  }
}

class NavigateTask : public EnvTask {
 public:
  NavigateTask(const EnvParams& params, const QuadParams& vehicle, const Map& map)
      : params_(params), bounds_(map.bounds), world_(map, Collision(vehicle)) {
    for (const Box& box : map.boxes) boxes_.push_back(box.extent);
    for (int k = 0; k < params.range_rays; ++k) {
      const double angle = 2.0 * kPi * k / params.range_rays;
      rays_.push_back(Vec3(std::cos(angle), std::sin(angle), 0.0));
    }
    rays_.push_back(-Vec3::UnitZ());
    rays_.push_back(Vec3::UnitZ());
    if (params.depth_width > 0) {
      DepthCameraParams camera;
      camera.width = params.depth_width;
      camera.height = params.depth_height;
      camera.range = params.range_max;
      camera_.emplace(camera, 0);  // exact: no noise, no dropouts, so the seed draws nothing
    }
    EnvRandom probe;
    probe.Seed(0);
    const std::optional<std::pair<Vec3, Vec3>> found = Endpoints(probe);
    if (!found) {
      const std::string where =
          params.map.empty() ? "the random forest (forest_trees)" : "map '" + params.map + "'";
      throw std::invalid_argument("navigate: no free start and goal " +
                                  FormatNumber(params.goal_distance) + " m apart in " + where +
                                  " after 1000 draws (goal_distance)");
    }
    fallback_ = *found;
  }

  State Begin(EnvRandom& random, const EnvOptions& options) override {
    // a crowded map may give no pair in 1000 draws: then the pair found when the task was made
    const std::pair<Vec3, Vec3> ends = Endpoints(random).value_or(fallback_);
    State s;
    s.p_W = ends.first;
    goal_ = ends.second;
    s.v_W = random.InBall(params_.start_speed);
    random.Attitude(params_, &s);
    if (options.start) s.p_W = *options.start;
    if (options.target) goal_ = *options.target;
    last_distance_ = (s.p_W - goal_).norm();
    return s;
  }

  void Check(const EnvOptions& options) const override {
    EnvTask::Check(options);
    if (options.start) Free(*options.start, "start");
    if (options.target) Free(*options.target, "target");
  }

  Vec3 Reference(double) const override { return goal_; }

  void Observe(double, const State& s, float* out) const override {
    for (size_t k = 0; k < rays_.size(); ++k) {
      out[k] = static_cast<float>(CastRay(boxes_, bounds_, s.p_W, rays_[k], params_.range_max));
    }
    if (!camera_) return;
    const DepthImage image = camera_->Capture(s, boxes_, bounds_);
    float* depth = out + rays_.size();
    for (size_t k = 0; k < image.depth.size(); ++k) {
      depth[k] = image.depth[k] > 0.0f ? image.depth[k] : static_cast<float>(params_.range_max);
    }
  }

  TaskScore Score(double, const State& s, const double* action) override {
    const double distance = (s.p_W - goal_).norm();
    const bool arrived = distance < params_.arrival_radius;
    TaskScore score;
    score.ended = arrived || !bounds_.Contains(s.p_W);
    score.terms = {params_.reward_alive, params_.reward_progress * (last_distance_ - distance)};
    AddMotionTerms(params_, s.v_W, s, action, &score.terms);
    score.terms.push_back(arrived ? params_.reward_arrival : 0.0);
    last_distance_ = distance;
    return score;
  }

 private:
  static CollisionParams Collision(const QuadParams& vehicle) {
    CollisionParams c;
    c.vehicle_size = vehicle.collision_size;
    c.clearance = 0.2;
    return c;
  }

  // std::invalid_argument naming the option when p is not free.
  void Free(const Vec3& p, const char* name) const {
    if (world_.IsPointFree(p)) return;
    throw std::invalid_argument(std::string("options[\"") + name + "\"] " + Point(p) +
                                " is not free: within 0.2 m of a box or the map's bounds");
  }

  // A start and a goal, both free and goal_distance apart, in up to 1000 draws.
  std::optional<std::pair<Vec3, Vec3>> Endpoints(EnvRandom& random) const {
    const Aabb& free = world_.free_bounds();
    const auto draw = [&] {
      return Vec3(random.Uniform(free.min.x(), free.max.x()),
                  random.Uniform(free.min.y(), free.max.y()),
                  random.Uniform(free.min.z(), std::min(free.max.z(), free.min.z() + 2.5)));
    };
    for (int tries = 0; tries < 1000; ++tries) {
      const Vec3 start = draw(), goal = draw();
      if ((goal - start).norm() >= params_.goal_distance && world_.IsPointFree(start) &&
          world_.IsPointFree(goal)) {
        return std::make_pair(start, goal);
      }
    }
    return std::nullopt;
  }

  EnvParams params_;
  Aabb bounds_;
  CollisionWorld world_;
  std::vector<Aabb> boxes_;
  std::vector<Vec3> rays_;
  mutable std::optional<DepthCamera> camera_;  // depth_width x depth_height; Capture keeps buffers
  std::pair<Vec3, Vec3> fallback_;             // a free start and goal, found when made
  Vec3 goal_;
  double last_distance_ = 0.0;
};

std::vector<std::string> RangeNames(const EnvParams& p) {
  std::vector<std::string> names;
  for (int k = 0; k < p.range_rays; ++k) names.push_back("range" + std::to_string(k));
  names.insert(names.end(), {"range_down", "range_up"});
  for (int v = 0; v < p.depth_height; ++v) {
    for (int u = 0; u < p.depth_width; ++u) {
      names.push_back("depth_" + std::to_string(v) + "_" + std::to_string(u));
    }
  }
  return names;
}

std::map<std::string, EnvTaskKind>& Registry() {
  static std::map<std::string, EnvTaskKind> kinds = [] {
    const std::vector<std::string> shared = {"alive", "position", "velocity", "rate", "action"};
    std::map<std::string, EnvTaskKind> k;
    k["hover"] = {
        "hover", [](const EnvParams&) { return std::vector<std::string>(); }, shared,
        [](const EnvParams& p) { return Room("env_hover", p.target, p.bounds_radius + 1.0); },
        [](const EnvParams& p, const QuadParams&, const Map&) {
          return std::unique_ptr<EnvTask>(new HoverTask(p));
        }};
    k["track"] = {"track", TrackNames, shared,
                  [](const EnvParams& p) {
                    return Room("env_track", p.target, p.bounds_radius + p.track_size + 1.0);
                  },
                  [](const EnvParams& p, const QuadParams&, const Map&) {
                    return std::unique_ptr<EnvTask>(new TrackTask(p));
                  }};
    k["navigate"] = {"navigate",
                     RangeNames,
                     {"alive", "progress", "velocity", "rate", "action", "arrival"},
                     NavigateMap,
                     [](const EnvParams& p, const QuadParams& v, const Map& m) {
                       return std::unique_ptr<EnvTask>(new NavigateTask(p, v, m));
                     }};
    return k;
  }();
  return kinds;
}

}  // namespace

void EnvTask::Check(const EnvOptions& options) const {
  CheckPoint(options.start, "start");
  CheckPoint(options.target, "target");
}

void EnvRandom::Seed(std::uint64_t seed) { rng_.seed(seed); }

double EnvRandom::Uniform() { return static_cast<double>(rng_() >> 11) * 0x1.0p-53; }

double EnvRandom::Uniform(double low, double high) { return low + (high - low) * Uniform(); }

// A direction from three normal draws (Box and Muller), a distance from the cube root.
Vec3 EnvRandom::InBall(double radius) {
  Vec3 d;
  for (int i = 0; i < 3; ++i) {
    const double u = 1.0 - Uniform(), v = Uniform();
    d[i] = std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * kPi * v);
  }
  const double n = d.norm();
  if (n < 1e-12) return Vec3::Zero();
  return d / n * (radius * std::cbrt(Uniform()));
}

void EnvRandom::Attitude(const EnvParams& params, State* s) {
  const double yaw = 2.0 * kPi * Uniform() - kPi;
  const double axis = 2.0 * kPi * Uniform();
  const double tilt = params.start_tilt * Uniform();
  s->q_WB = Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ())) *
            Quat(Eigen::AngleAxisd(tilt, Vec3(std::cos(axis), std::sin(axis), 0.0)));
  s->w_B = InBall(params.start_rate);
}

void RegisterEnvTask(EnvTaskKind kind) {
  const std::string name = kind.name;
  Registry()[name] = std::move(kind);
}

const EnvTaskKind& FindEnvTask(const std::string& name) {
  const auto& kinds = Registry();
  const auto found = kinds.find(name);
  if (found == kinds.end()) {
    throw std::invalid_argument("env.task '" + name + "': expected " + ListOfNames(EnvTaskNames()));
  }
  return found->second;
}

std::vector<std::string> EnvTaskNames() {
  std::vector<std::string> names;
  for (const auto& [name, kind] : Registry()) names.push_back(name);
  return names;
}

}  // namespace aerobox
