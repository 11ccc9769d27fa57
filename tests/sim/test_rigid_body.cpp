// The rigid body against MuJoCo: the same states under the same commands give the same states
// (one step, one control period), the same first touching step, the same warnings; and the models
// it does not reproduce are refused by name.
#include <doctest/doctest.h>

#include <random>
#include <string>

#include "scene/scene_mjcf.h"
#include "sim/rigid_body.h"
#include "sim/simulation.h"
#include "vehicle/quad_params.h"

namespace aerobox {
namespace {

double AngleBetween(const Quat& a, const Quat& b) { return a.angularDistance(b); }

struct Draw {
  std::mt19937_64 rng;
  double U(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
  Vec3 V(double r) { return Vec3(U(-r, r), U(-r, r), U(-r, r)); }
  Vec4 Thrusts(double lo, double hi) { return Vec4(U(lo, hi), U(lo, hi), U(lo, hi), U(lo, hi)); }
  State Any(const Vec3& centre) {
    State s;
    s.p_W = centre + V(0.3);
    s.q_WB = Quat(U(-1, 1), U(-1, 1), U(-1, 1), U(-1, 1)).normalized();
    s.v_W = V(3.0);
    s.w_B = V(20.0);
    return s;
  }
};

// Both physics in the same state, with the same produced thrusts and wrench.
void Place(const State& s, const Vec4& produced, const Vec3& force, const Vec3& torque,
           VehiclePhysics* physics) {
  physics->SetVehicleState(s);
  physics->SetProducedThrusts(produced);
  physics->SetExternalWrench(force, torque);
}

void CheckSame(const VehiclePhysics& a, const VehiclePhysics& b, double position, double angle) {
  const State x = a.VehicleState(), y = b.VehicleState();
  CHECK((x.p_W - y.p_W).norm() < position);
  CHECK(AngleBetween(x.q_WB, y.q_WB) < angle);
  CHECK((x.v_W - y.v_W).norm() < 1e3 * position);
  CHECK((x.w_B - y.w_B).norm() < 1e3 * angle);
  CHECK((a.RotorThrusts() - b.RotorThrusts()).norm() < 1e-12);
}

}  // namespace

TEST_CASE("one step and one control period of the rigid body are MuJoCo's") {
  for (const char* kind : {"tello", "crazyflie"}) {
    CAPTURE(kind);
    const QuadParams vehicle = *BuiltinVehicle(kind);
    Simulation sim = Simulation::FromXml(VehicleModelMjcf(vehicle), kind);
    RigidBody rigid(RigidModel::Of(sim));
    CHECK(rigid.timestep() == sim.timestep());
    Draw d{std::mt19937_64(7)};
    const double high = vehicle.MaxRotorThrust();
    for (int trial = 0; trial < 50; ++trial) {
      CAPTURE(trial);
      const State s = d.Any(Vec3(0, 0, 1));
      const Vec4 produced = d.Thrusts(0, high);
      const Vec3 force = d.V(0.1 * vehicle.mass * 9.81), torque = d.V(1e-4);
      Place(s, produced, force, torque, &sim);
      Place(s, produced, force, torque, &rigid);
      // commands beyond the rotors' range too: both clamp them
      const Vec4 command = d.Thrusts(-0.2 * high, 1.2 * high);
      sim.Step(command);
      rigid.Step(command);
      CheckSame(sim, rigid, 1e-12, 1e-12);
      CHECK((sim.LinearAcceleration_W() - rigid.LinearAcceleration_W()).norm() < 1e-9);
      CHECK((sim.AngularAcceleration_B() - rigid.AngularAcceleration_B()).norm() < 1e-7);
      // the rest of a 100 Hz control period (the bound: 1e-6 m and rad)
      for (int k = 1; k < 10; ++k) {
        sim.Step(command);
        rigid.Step(command);
      }
      CheckSame(sim, rigid, 1e-6, 1e-6);
      CHECK(sim.TakeNewWarnings().empty());
      CHECK(rigid.TakeNewWarnings().empty());
    }
  }
}

TEST_CASE("a turn of more than half a right angle in one step is MuJoCo's too") {
  // the half angle's sine and cosine come from a series up to pi/4, from the library beyond
  const QuadParams vehicle = *BuiltinVehicle("crazyflie");
  Simulation sim = Simulation::FromXml(VehicleModelMjcf(vehicle), "crazyflie");
  RigidBody rigid(RigidModel::Of(sim));
  Draw d{std::mt19937_64(13)};
  for (const double half_angle : {0.1, 0.7, 0.9, 2.0}) {
    CAPTURE(half_angle);
    State s = d.Any(Vec3(0, 0, 1));
    s.w_B = d.V(1.0).normalized() * (2.0 * half_angle / sim.timestep());
    Place(s, Vec4::Zero(), Vec3::Zero(), Vec3::Zero(), &sim);
    Place(s, Vec4::Zero(), Vec3::Zero(), Vec3::Zero(), &rigid);
    sim.Step(Vec4::Zero());
    rigid.Step(Vec4::Zero());
    CHECK(AngleBetween(sim.VehicleState().q_WB, rigid.VehicleState().q_WB) < 1e-12);
  }
}

TEST_CASE("a scaled vehicle (domain randomisation) is scaled alike") {
  const QuadParams vehicle = *BuiltinVehicle("crazyflie");
  Simulation sim = Simulation::FromXml(VehicleModelMjcf(vehicle), "crazyflie");
  RigidBody rigid(RigidModel::Of(sim));
  Draw d{std::mt19937_64(11)};
  for (int trial = 0; trial < 10; ++trial) {
    VehicleScaling s;
    s.mass = d.U(0.8, 1.2);
    s.inertia = Vec3(d.U(0.8, 1.2), d.U(0.8, 1.2), d.U(0.8, 1.2));
    s.thrust = d.Thrusts(0.8, 1.2);
    s.yaw_moment = d.Thrusts(0.8, 1.2);
    s.motor_lag = d.Thrusts(0.8, 1.2);
    s.rotor_limit = d.Thrusts(0.8, 1.2);
    sim.ScaleVehicle(s);
    rigid.ScaleVehicle(s);
    CheckSame(sim, rigid, 1e-15, 1e-15);  // both back to the model's start
    const State start = d.Any(Vec3(0, 0, 1));
    Place(start, d.Thrusts(0, 0.14), Vec3::Zero(), Vec3::Zero(), &sim);
    Place(start, sim.RotorThrusts(), Vec3::Zero(), Vec3::Zero(), &rigid);
    const Vec4 command = d.Thrusts(0, 0.2);
    for (int k = 0; k < 10; ++k) {
      sim.Step(command);
      rigid.Step(command);
    }
    CheckSame(sim, rigid, 1e-6, 1e-6);
  }
}

TEST_CASE("the first touching step is MuJoCo's, against the floor and random boxes") {
  const QuadParams vehicle = *BuiltinVehicle("crazyflie");
  Draw d{std::mt19937_64(5)};
  int touched = 0, floors = 0;
  for (int trial = 0; trial < 40; ++trial) {
    CAPTURE(trial);
    Map map;
    map.name = "boxes";
    map.bounds = {Vec3(-3, -3, 0), Vec3(3, 3, 3)};
    for (int b = 0; b < 6; ++b) {
      const Vec3 c(d.U(-1.5, 1.5), d.U(-1.5, 1.5), d.U(0.2, 2.5));
      const Vec3 h(d.U(0.05, 0.5), d.U(0.05, 0.5), d.U(0.05, 0.5));
      map.boxes.push_back({{c - h, c + h}, Vec3(0.5, 0.5, 0.5), "box_" + std::to_string(b), 0});
    }
    SceneOptions options;
    options.vehicle_position = Vec3(0, 0, 1.5);
    Simulation sim = Simulation::FromXml(BuildSceneMjcf(map, vehicle, options), "boxes");
    RigidBody rigid(RigidModel::Of(sim));
    REQUIRE(rigid.batch().model().boxes.size() == map.boxes.size());
    // a tumbling vehicle thrown from a free point at a random box (or the floor)
    State s;
    do {
      s = d.Any(Vec3(0, 0, 1.5));
      s.p_W = Vec3(d.U(-2.5, 2.5), d.U(-2.5, 2.5), d.U(0.3, 2.7));
      sim.SetVehicleState(s);
    } while (sim.VehicleTouches());
    const Aabb& aim = map.boxes[static_cast<size_t>(trial % 6)].extent;
    s.v_W = (trial % 7 == 0 ? Vec3(s.p_W.x(), s.p_W.y(), 0) : aim.Center()) - s.p_W;
    s.v_W = 4.0 * s.v_W.normalized();
    s.w_B = d.V(10);
    Place(s, Vec4::Zero(), Vec3::Zero(), Vec3::Zero(), &sim);
    Place(s, Vec4::Zero(), Vec3::Zero(), Vec3::Zero(), &rigid);
    int first_sim = -1, first_rigid = -1;
    for (int k = 0; k < 3000 && (first_sim < 0 || first_rigid < 0); ++k) {
      if (first_sim < 0) sim.Step(Vec4::Zero());
      if (first_rigid < 0) rigid.Step(Vec4::Zero());
      if (first_sim < 0 && sim.VehicleTouches()) first_sim = k;
      if (first_rigid < 0 && rigid.VehicleTouches()) first_rigid = k;
    }
    CHECK(first_sim == first_rigid);
    if (first_sim >= 0) {
      ++touched;
      const VehicleContact a = sim.VehicleContacts().front(), b = rigid.VehicleContacts().front();
      CHECK(a.other_geom == b.other_geom);
      // the depth in the state that touched: the floor's, MuJoCo's deepest corner; a box's, the
      // least overlap (MuJoCo's box-box contacts report it, or half of it, here)
      double deepest = 0.0;
      for (const VehicleContact& c : sim.VehicleContacts()) deepest = std::min(deepest, c.distance);
      CHECK(b.distance <= 0.0);
      if (a.other_geom == "floor") CHECK(b.distance == doctest::Approx(deepest).epsilon(1e-9));
      floors += a.other_geom == "floor";
    }
  }
  CHECK(touched >= 30);  // most throws hit something
  CHECK(floors >= 10);
}

TEST_CASE("a state that is no longer finite is a warning on both") {
  const QuadParams vehicle;
  Simulation sim = Simulation::FromXml(VehicleModelMjcf(vehicle), "tello");
  RigidBody rigid(RigidModel::Of(sim));
  State s;
  s.p_W = Vec3(0, 0, 1);
  s.v_W = Vec3(std::nan(""), 0, 0);
  for (VehiclePhysics* p :
       {static_cast<VehiclePhysics*>(&sim), static_cast<VehiclePhysics*>(&rigid)}) {
    p->TakeNewWarnings();
    p->SetVehicleState(s);
    p->Step(Vec4::Zero());
    CHECK_FALSE(p->TakeNewWarnings().empty());
    CHECK(p->VehicleState().AllFinite());  // reset
  }
}

TEST_CASE("models the rigid body does not reproduce are refused by name") {
  const std::string xml = VehicleModelMjcf(QuadParams());
  const auto refused = [](std::string text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    text.replace(at, from.size(), to);
    const Simulation sim = Simulation::FromXml(text, "changed");
    return RigidModel::Of(sim);
  };
  CHECK_THROWS_WITH(refused(xml, "<option ", "<option integrator=\"RK4\" "),
                    doctest::Contains("integrator"));
  CHECK_THROWS_WITH(refused(xml, "<option ", "<option density=\"1.2\" "),
                    doctest::Contains("density"));
  CHECK_THROWS_WITH(refused(xml, "<worldbody>", "<worldbody><geom name=\"ball\" size=\"0.1\"/>"),
                    doctest::Contains("ball"));
}

}  // namespace aerobox
