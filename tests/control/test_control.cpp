#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "control/cascade.h"
#include "control/inner_loops.h"
#include "control/se3_control.h"
#include "scene/scene_mjcf.h"
#include "sim/simulation.h"

namespace aerobox {
namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace

TEST_CASE("position control: hover needs m g along z, a push forward tilts forward, limits hold") {
  const QuadParams vehicle;
  PositionController control(PositionControlParams(), vehicle.mass);
  AttitudeSetpoint out;
  PositionSetpoint hold;
  hold.p_W = Vec3(0, 0, 1);
  REQUIRE(control.Update(hold, Vec3(0, 0, 1), Vec3::Zero(), Quat::Identity(), 0.004, &out));
  CHECK(out.thrust == doctest::Approx(vehicle.mass * kGravity));
  CHECK((out.q_WB * Vec3::UnitZ()).isApprox(Vec3::UnitZ()));

  PositionSetpoint ahead = hold;
  ahead.a_W = Vec3(2, 0, 0);  // accelerate along +x: the body z leans towards +x
  REQUIRE(control.Update(ahead, Vec3(0, 0, 1), Vec3::Zero(), Quat::Identity(), 0.004, &out));
  CHECK((out.q_WB * Vec3::UnitZ()).x() > 0.1);

  PositionSetpoint far = hold;
  far.a_W = Vec3(100, 0, 0);  // asks for far more than the tilt limit allows
  REQUIRE(control.Update(far, Vec3(0, 0, 1), Vec3::Zero(), Quat::Identity(), 0.004, &out));
  const double tilt = std::acos((out.q_WB * Vec3::UnitZ()).z());
  CHECK(tilt <= PositionControlParams().max_tilt + 1e-9);
}

TEST_CASE("every stage rejects non-finite input without throwing and keeps its output") {
  const QuadParams vehicle;
  PositionController position(PositionControlParams(), vehicle.mass);
  AttitudeSetpoint attitude;
  attitude.thrust = 42;
  PositionSetpoint bad;
  bad.p_W = Vec3(kNaN, 0, 0);
  CHECK_FALSE(position.Update(bad, Vec3::Zero(), Vec3::Zero(), Quat::Identity(), 0.004, &attitude));
  CHECK_FALSE(position.Update(PositionSetpoint(), Vec3::Zero(), Vec3(0, kNaN, 0), Quat::Identity(),
                              0.004, &attitude));
  CHECK_FALSE(position.Update(PositionSetpoint(), Vec3::Zero(), Vec3::Zero(), Quat::Identity(), 0.0,
                              &attitude));
  CHECK(attitude.thrust == 42);

  const AttitudeController attitude_control{AttitudeControlParams()};
  Vec3 rate = Vec3::Constant(7);
  CHECK_FALSE(attitude_control.Update(Quat(kNaN, 0, 0, 0), Quat::Identity(), &rate));
  CHECK(rate == Vec3::Constant(7));

  RateController rate_control(RateControlParams(), vehicle.inertia);
  Vec3 torque = Vec3::Constant(3);
  CHECK_FALSE(rate_control.Update(Vec3(kNaN, 0, 0), Vec3::Zero(), 0.001, false, &torque));
  CHECK(torque == Vec3::Constant(3));

  const Mixer mixer(vehicle);
  MixerOutput mixed;
  CHECK_FALSE(mixer.Mix(kNaN, Vec3::Zero(), &mixed));
  CHECK(mixed.thrusts == Vec4::Zero());

  CascadeController cascade(PositionControlParams(), 0.004, vehicle.mass);
  ControlCommand command;
  State state;
  state.w_B = Vec3(kNaN, 0, 0);
  CHECK_NOTHROW(CHECK_FALSE(cascade.Update(0.0, state, FlatOutput(), &command)));
  InnerLoops inner(InnerLoopParams(), vehicle);
  InnerOutput out;
  out.mixer.thrusts = Vec4::Constant(1);
  CHECK_NOTHROW(CHECK_FALSE(inner.Run(ControlCommand(), state, 0.001, &out)));
  CHECK(out.mixer.thrusts == Vec4::Zero());
  Se3Controller se3(Se3Params(), vehicle);
  CHECK_NOTHROW(CHECK_FALSE(se3.Update(0.0, state, FlatOutput(), &command)));
}

TEST_CASE("attitude control: a tilt error gets full gain, a yaw error only its share") {
  const AttitudeControlParams params;
  const AttitudeController control(params);
  Vec3 rate;
  // 0.1 rad of roll error: roll rate = gain * 0.1 (small angle)
  REQUIRE(control.Update(Quat::Identity(), Quat(Eigen::AngleAxisd(0.1, Vec3::UnitX())), &rate));
  CHECK(rate.x() == doctest::Approx(params.gain.x() * 0.1).epsilon(0.01));
  CHECK(std::abs(rate.z()) < 1e-9);
  // 0.1 rad of yaw error: yaw rate = yaw gain * 0.1
  REQUIRE(control.Update(Quat::Identity(), Quat(Eigen::AngleAxisd(0.1, Vec3::UnitZ())), &rate));
  CHECK(rate.z() == doctest::Approx(params.gain.z() * 0.1).epsilon(0.01));
  // a large yaw error does not disturb the tilt correction
  const Quat both =
      Quat(Eigen::AngleAxisd(2.5, Vec3::UnitZ())) * Quat(Eigen::AngleAxisd(0.1, Vec3::UnitX()));
  REQUIRE(control.Update(Quat::Identity(), both, &rate));
  CHECK(std::hypot(rate.x(), rate.y()) == doctest::Approx(params.gain.x() * 0.1).epsilon(0.05));
}

TEST_CASE("mixer: exact inside the limits, thrust then roll/pitch before yaw when saturated") {
  const QuadParams vehicle;
  const Mixer mixer(vehicle);
  const Mat4 allocation = AllocationMatrix(vehicle);
  MixerOutput out;
  const Vec3 torque(1e-3, -2e-3, 1e-4);
  REQUIRE(mixer.Mix(0.8, torque, &out));
  Vec4 wrench;
  wrench << 0.8, torque;
  CHECK((allocation * out.thrusts - wrench).norm() < 1e-12);
  CHECK_FALSE(out.saturated());

  // a yaw demand beyond the rotors: thrust and roll kept, yaw cut
  REQUIRE(mixer.Mix(0.8, Vec3(2e-3, 0, 0.05), &out));
  const Vec4 delivered = allocation * out.thrusts;
  CHECK(delivered[0] == doctest::Approx(0.8));
  CHECK(delivered[1] == doctest::Approx(2e-3));
  CHECK(out.yaw_scale < 1.0);
  CHECK(out.thrusts.minCoeff() >= 0.0);
  CHECK(out.thrusts.maxCoeff() <= vehicle.MaxRotorThrust() + 1e-12);

  // a roll demand beyond the rotors at full thrust: thrust kept, roll cut, yaw gone
  REQUIRE(mixer.Mix(1.5, Vec3(0.05, 0, 0.01), &out));
  CHECK((allocation * out.thrusts)[0] == doctest::Approx(1.5));
  CHECK(out.roll_pitch_scale < 1.0);
  CHECK(out.thrusts.maxCoeff() <= vehicle.MaxRotorThrust() + 1e-12);
}

TEST_CASE("the mixer's predicted body acceleration matches MuJoCo's response") {
  const QuadParams vehicle;
  Map room;
  room.name = "room";
  room.bounds = {Vec3(-2, -2, 0), Vec3(2, 2, 3)};
  SceneOptions options;
  options.vehicle_position = Vec3(0, 0, 1.5);
  Simulation sim = Simulation::FromXml(BuildSceneMjcf(room, vehicle, options), "room");
  const Mixer mixer(vehicle);
  for (const Vec3& torque :
       {Vec3(2e-3, 0, 0), Vec3(0, -1.5e-3, 0), Vec3(0, 0, 4e-4), Vec3(1e-3, 1e-3, -2e-4)}) {
    CAPTURE(torque.transpose());
    const double thrust = 1.1 * vehicle.mass * kGravity;
    MixerOutput out;
    REQUIRE(mixer.Mix(thrust, torque, &out));
    REQUIRE_FALSE(out.saturated());
    sim.SetVehicleState(State{Vec3(0, 0, 1.5), Vec3::Zero(), Quat::Identity(), Vec3::Zero()});
    sim.SetRotorThrusts(out.thrusts);
    // at rest, level: a = T/m - g along z, alpha = tau / J; MuJoCo agrees to rounding
    CHECK((sim.LinearAcceleration_W() - Vec3(0, 0, thrust / vehicle.mass - kGravity)).norm() <
          1e-9);
    CHECK((sim.AngularAcceleration_B() - torque.cwiseQuotient(vehicle.inertia)).norm() < 1e-6);
  }
}

}  // namespace aerobox
