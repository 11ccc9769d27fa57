#include "control/position_control.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/number_format.h"

namespace aerobox {

void PositionControlParams::Validate() const {
  const auto positive = [](const Vec3& v) { return v.allFinite() && (v.array() >= 0).all(); };
  if (!positive(position_gain) || !positive(velocity_gain) || !positive(velocity_integral) ||
      !positive(velocity_derivative) || !positive(integral_limit)) {
    throw std::invalid_argument("PositionControlParams: gains and limits must be >= 0");
  }
  for (const double limit :
       {max_speed_horizontal, max_speed_vertical, max_accel_horizontal, max_accel_vertical}) {
    if (!(limit > 0 && std::isfinite(limit))) {
      throw std::invalid_argument(
          "PositionControlParams: speed and acceleration limits must be > 0");
    }
  }
  if (!(max_tilt > 0 && max_tilt < M_PI / 2)) {
    throw std::invalid_argument("PositionControlParams.max_tilt must be in (0, pi/2), got " +
                                FormatNumber(max_tilt));
  }
  if (!(min_thrust_fraction > 0 && min_thrust_fraction < 1)) {
    throw std::invalid_argument("PositionControlParams.min_thrust_fraction must be in (0, 1)");
  }
}

Vec3 LimitSplit(const Vec3& v, double horizontal, double vertical) {
  Vec3 out = v;
  const double h = v.head<2>().norm();
  if (h > horizontal) out.head<2>() *= horizontal / h;
  out.z() = std::clamp(v.z(), -vertical, vertical);
  return out;
}

PositionController::PositionController(const PositionControlParams& params, double mass)
    : params_(params), mass_(mass) {
  params_.Validate();
  if (!(mass > 0)) throw std::invalid_argument("PositionController: mass must be > 0");
}

bool PositionController::Update(const PositionSetpoint& setpoint, const Vec3& p_W, const Vec3& v_W,
                                const Quat& q_WB, double dt, AttitudeSetpoint* out) {
  if (!(dt > 0) || !setpoint.p_W.allFinite() || !setpoint.v_W.allFinite() ||
      !setpoint.a_W.allFinite() || !std::isfinite(setpoint.yaw) || !p_W.allFinite() ||
      !v_W.allFinite() || !q_WB.coeffs().allFinite()) {
    return false;
  }
  // position P -> velocity setpoint (feed-forward plus correction), limited
  const Vec3 v_sp =
      LimitSplit(setpoint.v_W + params_.position_gain.cwiseProduct(setpoint.p_W - p_W),
                 params_.max_speed_horizontal, params_.max_speed_vertical);
  // velocity PID -> acceleration setpoint
  const Vec3 error = v_sp - v_W;
  const Vec3 unlimited = setpoint.a_W + params_.velocity_gain.cwiseProduct(error) + integral_;
  const Vec3 a_sp = LimitSplit(unlimited, params_.max_accel_horizontal, params_.max_accel_vertical);
  // anti-windup: integrate only while the output is not limited (or the error unwinds it)
  const Vec3 step = params_.velocity_integral.cwiseProduct(error) * dt;
  for (int k = 0; k < 3; ++k) {
    const bool limited = std::abs(a_sp[k] - unlimited[k]) > 1e-9;
    if (!limited || step[k] * integral_[k] < 0) {
      integral_[k] =
          std::clamp(integral_[k] + step[k], -params_.integral_limit[k], params_.integral_limit[k]);
    }
  }

  // thrust vector: what must push against gravity plus the acceleration; its tilt is limited
  // by shrinking the horizontal part (the vertical part, holding altitude, comes first)
  Vec3 force = mass_ * (a_sp + Vec3(0, 0, kGravity));
  force.z() = std::max(force.z(), params_.min_thrust_fraction * mass_ * kGravity);
  const double max_horizontal = force.z() * std::tan(params_.max_tilt);
  if (force.head<2>().norm() > max_horizontal) {
    force.head<2>() *= max_horizontal / force.head<2>().norm();
  }

  // desired attitude: body z along the force, body x as close to the yaw heading as it can be
  const Vec3 b3 = force.normalized();
  const Vec3 heading(std::cos(setpoint.yaw), std::sin(setpoint.yaw), 0.0);
  Vec3 b2 = b3.cross(heading);
  if (b2.norm() < 1e-6) b2 = b3.cross(Vec3::UnitX());  // thrust along the heading: not flyable
  b2.normalize();
  Mat3 r;
  r << b2.cross(b3), b2, b3;
  out->q_WB = Quat(r).normalized();
  // collective thrust: the part of the force the current body z can deliver
  out->thrust = std::max(0.0, force.dot(q_WB * Vec3::UnitZ()));
  out->a_W = a_sp;
  out->v_W = v_sp;
  return true;
}

}  // namespace aerobox
