#include "control/cascade.h"

#include <stdexcept>

namespace aerobox {

CascadeController::CascadeController(const PositionControlParams& params, double period,
                                     double mass)
    : position_(params, mass), period_(period) {
  if (!(period > 0)) throw std::invalid_argument("CascadeController: period must be > 0");
  last_.thrust = mass * kGravity;
}

Vec3 RateFeedForward(const FlatOutput& setpoint, const Quat& q_WB) {
  // the thrust axis turns with the part of the jerk across it, at 1 / |a + g| (Mellinger and
  // Kumar 2011, eq. 7); yaw turns about the world's z
  const Vec3 thrust = setpoint.a_W + Vec3(0, 0, kGravity);
  const double norm = thrust.norm();
  if (!(norm > 1e-3) || !setpoint.j_W.allFinite()) return Vec3::Zero();
  const Mat3 R = q_WB.toRotationMatrix();
  const Vec3 z_b = R.col(2);
  const Vec3 h = (setpoint.j_W - z_b.dot(setpoint.j_W) * z_b) / norm;
  return Vec3(-h.dot(R.col(1)), h.dot(R.col(0)), setpoint.yaw_rate * z_b.z());
}

ControlStatus CascadeController::Update(double, const State& state, const FlatOutput& setpoint,
                                        ControlCommand* command) {
  PositionSetpoint target;
  target.p_W = setpoint.p_W;
  target.v_W = setpoint.v_W;
  target.a_W = setpoint.a_W;
  target.yaw = setpoint.yaw;
  if (!state.w_B.allFinite() ||
      !position_.Update(target, state.p_W, state.v_W, state.q_WB, period_, &last_)) {
    return ControlStatus::NonFinite();
  }
  command->level = CommandLevel::kThrustAttitude;
  command->thrust = last_.thrust;
  command->q_WB = last_.q_WB;
  command->rate_B = RateFeedForward(setpoint, last_.q_WB);
  return ControlStatus::Ok();
}

std::vector<std::string> CascadeController::ReportColumns() const {
  return {"vx_sp", "vy_sp", "vz_sp", "ax_sp", "ay_sp", "az_sp"};
}

void CascadeController::Report(std::vector<double>* values) const {
  *values = {last_.v_W.x(), last_.v_W.y(), last_.v_W.z(),
             last_.a_W.x(), last_.a_W.y(), last_.a_W.z()};
}

}  // namespace aerobox
