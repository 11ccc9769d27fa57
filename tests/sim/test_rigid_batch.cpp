// The rigid bodies of a batch: each world steps exactly as a body of its own, to the bit, however
// the batch is cut into ranges (its threads' blocks, runs of active worlds), with contacts and
// warnings its own.
#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "scene/scene_mjcf.h"
#include "sim/rigid_batch.h"
#include "sim/rigid_body.h"
#include "sim/simulation.h"
#include "vehicle/quad_params.h"

namespace aerobox {
namespace {

// A Crazyflie among boxes over a floor: the model the worlds are made from.
RigidModel BoxesModel() {
  const QuadParams vehicle = *BuiltinVehicle("crazyflie");
  Map map;
  map.name = "boxes";
  map.bounds = {Vec3(-2, -2, 0), Vec3(2, 2, 2)};
  map.boxes.push_back({{Vec3(0.3, -1, 0), Vec3(0.6, 1, 2)}, Vec3(0.5, 0.5, 0.5), "wall", 0});
  map.boxes.push_back({{Vec3(-1, -1, 1.6), Vec3(1, 1, 1.7)}, Vec3(0.5, 0.5, 0.5), "roof", 0});
  SceneOptions options;
  options.vehicle_position = Vec3(-1, 0, 1);
  return RigidModel::Of(Simulation::FromXml(BuildSceneMjcf(map, vehicle, options), "boxes"));
}

struct Draw {
  std::mt19937_64 rng;
  double U(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
  Vec3 V(double r) { return Vec3(U(-r, r), U(-r, r), U(-r, r)); }
  Vec4 Thrusts(double hi) { return Vec4(U(-0.1, hi), U(0, hi), U(0, hi), U(0, hi)); }
};

// Every world's state, thrusts, accelerations, contacts and warnings are the same bits.
void CheckSameBits(VehiclePhysics& a, VehiclePhysics& b) {
  const State x = a.VehicleState(), y = b.VehicleState();
  CHECK(x.p_W == y.p_W);
  CHECK(x.q_WB.coeffs() == y.q_WB.coeffs());
  CHECK(x.v_W == y.v_W);
  CHECK(x.w_B == y.w_B);
  CHECK(a.RotorThrusts() == b.RotorThrusts());
  CHECK(a.LinearAcceleration_W() == b.LinearAcceleration_W());
  CHECK(a.AngularAcceleration_B() == b.AngularAcceleration_B());
  CHECK(a.VehicleTouches() == b.VehicleTouches());
  CHECK(a.VehicleContacts().size() == b.VehicleContacts().size());
  CHECK(a.TakeNewWarnings() == b.TakeNewWarnings());
  CHECK(a.time() == b.time());
}

}  // namespace

TEST_CASE("a batch's worlds step as bodies of their own, to the bit, however it is cut") {
  const RigidModel model = BoxesModel();
  constexpr int kWorlds = 11;  // odd: the vectorised loops' remainders too
  // the same worlds three times: stepped whole, in uneven ranges, and each a body of its own
  RigidBatch whole(model, kWorlds), cut(model, kWorlds);
  std::vector<std::unique_ptr<RigidBody>> alone, in_whole, in_cut;
  for (int i = 0; i < kWorlds; ++i) {
    alone.push_back(std::make_unique<RigidBody>(model));
    in_whole.push_back(std::make_unique<RigidBody>(&whole, i));
    in_cut.push_back(std::make_unique<RigidBody>(&cut, i));
  }
  Draw d{std::mt19937_64(3)};
  const double high = model.command_max[0];
  int touching = 0, warned = 0;
  for (int i = 0; i < kWorlds; ++i) {
    State s;
    s.p_W = Vec3(d.U(-1.5, 1.5), d.U(-1.5, 1.5), d.U(0.2, 1.5));
    s.q_WB = Quat(d.U(-1, 1), d.U(-1, 1), d.U(-1, 1), d.U(-1, 1)).normalized();
    s.v_W = d.V(2.0);
    s.w_B = d.V(10.0);
    VehicleScaling scaling;  // each world its own vehicle
    scaling.mass = d.U(0.8, 1.2);
    scaling.thrust = Vec4::Constant(d.U(0.8, 1.2));
    const Vec3 force = d.V(0.05), torque = d.V(1e-5);
    for (auto* body : {alone[i].get(), in_whole[i].get(), in_cut[i].get()}) {
      body->ScaleVehicle(scaling);
      body->SetVehicleState(s);
      body->SetExternalWrench(force, torque);
    }
  }
  for (int step = 0; step < 300; ++step) {
    CAPTURE(step);
    if (step == 200) {  // a state no longer finite: this world's warning and reset alone
      State s = cut.VehicleState(7);
      s.v_W.x() = std::nan("");
      for (auto* body : {alone[7].get(), in_whole[7].get(), in_cut[7].get()}) {
        body->SetVehicleState(s);
      }
    }
    for (int i = 0; i < kWorlds; ++i) {
      Vec4 commands = d.Thrusts(1.2 * high);
      if (i == 4 && step == 100) commands[2] = std::nan("");  // a bad command: this world's alone
      whole.SetCommands(i, commands);
      cut.SetCommands(i, commands);
      alone[static_cast<size_t>(i)]->Step(commands);
    }
    whole.Step(0, kWorlds);
    cut.Step(0, 2);
    cut.Step(2, 3);
    cut.Step(3, kWorlds);
    for (int i = 0; i < kWorlds; ++i) {
      CAPTURE(i);
      touching += alone[static_cast<size_t>(i)]->VehicleTouches();
      warned += !whole.TakeNewWarnings(i).empty();
      CheckSameBits(*alone[static_cast<size_t>(i)], *in_cut[static_cast<size_t>(i)]);
    }
  }
  CHECK(touching > 0);  // some worlds met a box or the floor
  CHECK(warned == 2);   // the bad command and the state no longer finite, each once
  // the whole batch's worlds are the cut batch's too
  for (int i = 0; i < kWorlds; ++i) {
    CHECK(whole.VehicleState(i).p_W == cut.VehicleState(i).p_W);
    CHECK(whole.VehicleState(i).q_WB.coeffs() == cut.VehicleState(i).q_WB.coeffs());
  }
}

TEST_CASE("a batch refuses no worlds, and a view refuses a world outside it") {
  const RigidModel model = BoxesModel();
  CHECK_THROWS_AS(RigidBatch(model, 0), std::invalid_argument);
  RigidBatch batch(model, 2);
  CHECK_THROWS_AS(RigidBody(&batch, 2), std::out_of_range);
  CHECK_THROWS_AS(RigidBody(&batch, -1), std::out_of_range);
  CHECK_THROWS_AS(RigidBody(nullptr, 0), std::out_of_range);
}

}  // namespace aerobox
