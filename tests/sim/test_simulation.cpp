// Physics cross-checks: MuJoCo's response to rotor thrusts against the allocation matrix.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "common/error.h"
#include "scene/scene_mjcf.h"
#include "sim/mujoco_messages.h"
#include "sim/simulation.h"

namespace aerobox {
namespace {

// The vehicle alone, held 1 m above the floor, at rest, level.
Simulation HoveringVehicle(const QuadParams& params) {
  Simulation sim = Simulation::FromXml(VehicleModelMjcf(params), "tello");
  State state;
  state.p_W = Vec3(0, 0, 1);
  sim.SetVehicleState(state);
  return sim;
}

}  // namespace

TEST_CASE("with each rotor at m g / 4 the vehicle does not accelerate") {
  const QuadParams params;
  TakeMujocoWarnings();
  Simulation sim = HoveringVehicle(params);
  sim.SetRotorThrusts(Vec4::Constant(params.HoverThrustPerRotor()));
  // exact balance in the model, so only rounding remains
  CHECK(sim.LinearAcceleration_W().norm() < 1e-9);
  CHECK(sim.AngularAcceleration_B().norm() < 1e-9);
  for (int i = 0; i < 1000; ++i) sim.Step(Vec4::Constant(params.HoverThrustPerRotor()));
  // after 1 s of hover the vehicle has not moved by more than rounding accumulates
  CHECK((sim.VehicleState().p_W - Vec3(0, 0, 1)).norm() < 1e-6);
  CHECK(sim.VehicleContacts().empty());
  CHECK(TakeMujocoWarnings().empty());
}

TEST_CASE("unequal thrusts rotate the body as the allocation matrix predicts") {
  const QuadParams params;
  const Mat4 allocation = AllocationMatrix(params);
  const double hover = params.HoverThrustPerRotor();
  const double delta = 0.02;  // [N] per rotor, well inside [0, max]
  const std::pair<const char*, Vec4> cases[] = {
      {"roll: left rotors up", Vec4(delta, -delta, -delta, delta)},
      {"pitch: back rotors up", Vec4(-delta, -delta, delta, delta)},
      {"yaw: clockwise rotors up", Vec4(delta, -delta, delta, -delta)},
      {"mixed", Vec4(delta, 0.5 * delta, -0.3 * delta, 0)},
  };
  for (const auto& [name, change] : cases) {
    CAPTURE(name);
    Simulation sim = HoveringVehicle(params);
    const Vec4 thrusts = Vec4::Constant(hover) + change;
    sim.SetRotorThrusts(thrusts);
    const Vec4 wrench = allocation * thrusts;
    // at rest (w = 0) Euler's equations reduce to I alpha = moment
    const Vec3 predicted_alpha = wrench.tail<3>().cwiseQuotient(params.inertia);
    const Vec3 predicted_accel = Vec3(0, 0, wrench[0] / params.mass - kGravity);
    // MuJoCo solves the same rigid-body equations: agreement to solver rounding
    CHECK((sim.AngularAcceleration_B() - predicted_alpha).norm() <=
          1e-9 * predicted_alpha.norm() + 1e-9);
    CHECK((sim.LinearAcceleration_W() - predicted_accel).norm() < 1e-9);
    // and the body really turns that way after a short time
    for (int i = 0; i < 50; ++i) sim.Step(thrusts);
    const Vec3 w = sim.VehicleState().w_B;
    for (int k = 0; k < 3; ++k) {
      if (std::abs(predicted_alpha[k]) > 1.0) CHECK(w[k] * predicted_alpha[k] > 0);
    }
  }
}

TEST_CASE("motor lag: thrust follows a step command as a first-order filter") {
  const QuadParams params;
  Simulation sim = HoveringVehicle(params);
  const double command = 0.3;
  const int steps = static_cast<int>(std::lround(params.motor_time_constant / sim.timestep()));
  for (int i = 0; i < steps; ++i) sim.Step(Vec4::Constant(command));
  // one time constant: 1 - (1 - dt/tau)^n with MuJoCo's explicit Euler update, ~ 1 - 1/e
  const double expected =
      command * (1 - std::pow(1 - sim.timestep() / params.motor_time_constant, steps));
  CHECK(sim.RotorThrusts()[0] == doctest::Approx(expected).epsilon(1e-6));
  CHECK(sim.RotorThrusts()[0] == doctest::Approx(command * (1 - std::exp(-1))).epsilon(0.03));
  // commands beyond the rotor's limit are clamped
  for (int i = 0; i < 500; ++i) sim.Step(Vec4::Constant(10.0));
  CHECK(sim.RotorThrusts().maxCoeff() <= params.max_rotor_thrust + 1e-12);
}

TEST_CASE("contacts name the geom the vehicle touches") {
  const QuadParams params;
  Map map;
  map.name = "wall";
  map.bounds = {Vec3(0, 0, 0), Vec3(4, 4, 3)};
  map.boxes.push_back({{Vec3(2, 0, 0), Vec3(2.5, 4, 3)}, Vec3(1, 0, 0), "wall", 1});
  SceneOptions options;
  options.vehicle_position = VehicleRestPosition(map, params, Vec3(1, 2, 0));
  Simulation sim = Simulation::FromXml(BuildSceneMjcf(map, params, options), "wall");
  // resting on the floor
  for (int i = 0; i < 200; ++i) sim.Step(Vec4::Zero());
  const std::vector<VehicleContact> on_floor = sim.VehicleContacts();
  REQUIRE_FALSE(on_floor.empty());
  CHECK(on_floor[0].other_geom == "floor");
  CHECK(sim.VehicleState().p_W.z() == doctest::Approx(0.025).epsilon(0.05));
  // pushed into the wall
  State state;
  state.p_W = Vec3(1.97, 2, 1.5);
  sim.SetVehicleState(state);
  const std::vector<VehicleContact> contacts = sim.VehicleContacts();
  REQUIRE(contacts.size() >= 1);
  CHECK(contacts[0].other_geom == "wall");
  CHECK(contacts[0].distance < 0);
}

TEST_CASE("loading errors are InputErrors naming the source") {
  CHECK_THROWS_AS(Simulation::FromXml("<mujoco><worldbody><geom size='1'/>", "broken"), InputError);
  CHECK_THROWS_WITH(Simulation::FromXml("<mujoco/>", "empty"),
                    doctest::Contains("quad: the model has no element"));
}

}  // namespace aerobox

namespace aerobox {
namespace {

// `steps` of uneven, varying commands [N] from a tilted, turning start; the states along.
std::vector<State> Fly(Simulation sim, double command_scale, int steps) {
  State start;
  start.p_W = Vec3(0, 0, 1);
  start.q_WB = Quat(Eigen::AngleAxisd(0.2, Vec3(1, 1, 0).normalized()));
  start.w_B = Vec3(0.3, -0.2, 0.5);
  sim.SetVehicleState(start);
  std::vector<State> states;
  for (int k = 0; k < steps; ++k) {
    const Vec4 c(0.18 + 0.05 * std::sin(0.01 * k), 0.2, 0.21 + 0.04 * std::cos(0.02 * k), 0.19);
    sim.Step(c * command_scale);
    states.push_back(sim.VehicleState());
  }
  return states;
}

void CheckSame(const std::vector<State>& a, const std::vector<State>& b, double tolerance) {
  REQUIRE(a.size() == b.size());
  for (size_t k = 0; k < a.size(); ++k) {
    CHECK((a[k].p_W - b[k].p_W).norm() < tolerance);
    CHECK(a[k].q_WB.angularDistance(b[k].q_WB) < tolerance);
  }
}

}  // namespace

TEST_CASE("a scaled vehicle flies as a model made with the scaled values") {
  const QuadParams nominal;
  QuadParams varied = nominal;
  varied.mass *= 1.1;
  varied.inertia = nominal.inertia.cwiseProduct(Vec3(0.95, 1.05, 1.1));
  varied.yaw_moment_per_thrust *= 0.8;
  varied.motor_time_constant *= 1.3;
  varied.max_rotor_thrust *= 0.9;
  VehicleScaling scaling;
  scaling.mass = 1.1;
  scaling.inertia = Vec3(0.95, 1.05, 1.1);
  scaling.yaw_moment = Vec4::Constant(0.8);
  scaling.motor_lag = Vec4::Constant(1.3);
  scaling.rotor_limit = Vec4::Constant(0.9);
  Simulation scaled = Simulation::FromXml(VehicleModelMjcf(nominal), "nominal");
  scaled.ScaleVehicle(scaling);
  const Simulation made = Simulation::FromXml(VehicleModelMjcf(varied), "varied");
  const std::vector<State> a = Fly(scaled.Clone(), 1.0, 2000), b = Fly(made.Clone(), 1.0, 2000);
  CheckSame(a, b, 1e-9);
  CHECK((a.back().p_W -
         Fly(Simulation::FromXml(VehicleModelMjcf(nominal), "n"), 1.0, 2000).back().p_W)
            .norm() > 0.01);  // and the scaling did change the flight
  // not cumulative: scaling back to ones is the nominal vehicle again
  scaled.ScaleVehicle(VehicleScaling());
  CheckSame(Fly(scaled.Clone(), 1.0, 500),
            Fly(Simulation::FromXml(VehicleModelMjcf(nominal), "n"), 1.0, 500), 1e-12);
  // a rotor that produces 1.1 N per newton commanded flies as the nominal one commanded 1.1 x
  VehicleScaling stronger;
  stronger.thrust = Vec4::Constant(1.1);
  Simulation strong = Simulation::FromXml(VehicleModelMjcf(nominal), "nominal");
  strong.ScaleVehicle(stronger);
  CheckSame(Fly(strong.Clone(), 1.0, 1000),
            Fly(Simulation::FromXml(VehicleModelMjcf(nominal), "n"), 1.1, 1000), 1e-9);
}

}  // namespace aerobox
