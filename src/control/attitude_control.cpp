#include "control/attitude_control.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace aerobox {

void AttitudeControlParams::Validate() const {
  if (!gain.allFinite() || (gain.array() <= 0).any() || !max_rate.allFinite() ||
      (max_rate.array() <= 0).any() || !(yaw_weight > 0 && yaw_weight <= 1)) {
    throw std::invalid_argument(
        "AttitudeControlParams: gains and rate limits must be > 0, yaw_weight in (0, 1]");
  }
}

AttitudeController::AttitudeController(const AttitudeControlParams& params) : params_(params) {
  params_.Validate();
}

bool AttitudeController::Update(const Quat& q_WB, const Quat& q_WB_desired, Vec3* rate_B) const {
  if (!q_WB.coeffs().allFinite() || !q_WB_desired.coeffs().allFinite()) return false;
  const Quat q = q_WB.normalized();
  Quat q_d = q_WB_desired.normalized();

  // the reduced desired attitude: the current one, tilted the shortest way onto the desired
  // thrust direction (no yaw change)
  const Vec3 z = q * Vec3::UnitZ();
  const Vec3 z_d = q_d * Vec3::UnitZ();
  const Quat q_reduced = (Quat::FromTwoVectors(z, z_d) * q).normalized();

  // what remains is a rotation about the desired z (yaw); keep only yaw_weight of it
  Quat q_mix = q_reduced.inverse() * q_d;
  if (q_mix.w() < 0) q_mix.coeffs() *= -1;  // the short way round
  const double half_angle = std::atan2(q_mix.z(), q_mix.w());
  const double w = params_.yaw_weight;
  q_d = q_reduced * Quat(std::cos(w * half_angle), 0, 0, std::sin(w * half_angle));

  // the error rotation in the body frame, as a rotation vector (2 * vector part for small
  // angles), times the gains
  Quat q_error = q.inverse() * q_d;
  if (q_error.w() < 0) q_error.coeffs() *= -1;
  Vec3 gain = params_.gain;
  gain.z() /= params_.yaw_weight;  // undo the weight's scaling for small yaw errors
  const Vec3 rate = gain.cwiseProduct(2.0 * q_error.vec());
  *rate_B = rate.cwiseMax(-params_.max_rate).cwiseMin(params_.max_rate);
  return true;
}

}  // namespace aerobox
