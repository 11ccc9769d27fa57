// Attitude control on quaternions with reduced yaw priority (Brescianini, Hehn and D'Andrea 2013,
// "Nonlinear quadrocopter attitude control"; the split PX4 uses): the thrust direction is
// corrected first, at full gain, and only a fraction of the yaw error, so that a large yaw error
// never costs tilt authority. Output: body-rate setpoint.
#pragma once

#include "common/types.h"

namespace aerobox {

struct AttitudeControlParams {
  Vec3 gain = Vec3(8.0, 8.0, 4.0);        // [1/s] rate per radian of error, roll, pitch, yaw
  Vec3 max_rate = Vec3(12.0, 12.0, 4.0);  // [rad/s] body-rate setpoint limits
  // Fraction of the yaw error mixed into the attitude target, in (0, 1] (PX4's MC_YAW_WEIGHT);
  // the yaw gain is divided by it, so small yaw errors still see `gain.z()`.
  double yaw_weight = 0.4;

  void Validate() const;
};

class AttitudeController {
 public:
  explicit AttitudeController(const AttitudeControlParams& params);

  // Returns false for non-finite inputs (out untouched); never throws.
  bool Update(const Quat& q_WB, const Quat& q_WB_desired, Vec3* rate_B) const;

 private:
  AttitudeControlParams params_;
};

}  // namespace aerobox
