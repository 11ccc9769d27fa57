// Body-rate PID (after PX4's RateControl) producing torques: gains are in angular acceleration
// per rate error and are multiplied by the inertia, so they carry over between vehicle sizes;
// the gyroscopic term w x Jw is compensated.
#pragma once

#include "common/types.h"

namespace aerobox {

struct RateControlParams {
  Vec3 gain = Vec3(40.0, 40.0, 20.0);            // [1/s] angular acceleration per rad/s of error
  Vec3 integral = Vec3(20.0, 20.0, 10.0);        // [1/s^2]
  Vec3 derivative = Vec3(0.0, 0.0, 0.0);         // [-] on the measured rate
  Vec3 integral_limit = Vec3(10.0, 10.0, 10.0);  // [rad/s^2] anti-windup clamp

  void Validate() const;
};

class RateController {
 public:
  RateController(const RateControlParams& params, const Vec3& inertia);

  // Torque [N m, body] for the rate setpoint. `saturated` says the mixer could not deliver the
  // last torque: the integral then holds (anti-windup). Returns false for non-finite inputs
  // or dt <= 0 (out untouched); never throws.
  bool Update(const Vec3& rate_setpoint_B, const Vec3& w_B, double dt, bool saturated,
              Vec3* torque_B);

  void Reset() {
    integral_.setZero();
    previous_w_.setZero();
  }

 private:
  RateControlParams params_;
  Vec3 inertia_;
  Vec3 integral_ = Vec3::Zero();
  Vec3 previous_w_ = Vec3::Zero();
};

}  // namespace aerobox
