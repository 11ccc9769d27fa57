// The outer loops of the cascade (after PX4's PositionControl): position P -> velocity PID with
// feed-forward -> desired acceleration -> thrust vector with a tilt limit -> collective thrust
// and desired attitude. Pure math; update() checks its inputs and says whether its output can
// be used. ENU world frame, z up (PX4 is NED: its signs are not ours).
#pragma once

#include "common/types.h"

namespace aerobox {

struct PositionControlParams {
  Vec3 position_gain = Vec3(1.8, 1.8, 2.5);        // [1/s] velocity setpoint per metre of error
  Vec3 velocity_gain = Vec3(4.0, 4.0, 6.0);        // [1/s] acceleration per m/s of error
  Vec3 velocity_integral = Vec3(0.8, 0.8, 2.0);    // [1/s^2]
  Vec3 velocity_derivative = Vec3(0.0, 0.0, 0.0);  // [-] on the measured acceleration
  double max_speed_horizontal = 8.0;          // [m/s] velocity setpoint limit (a Tello's top speed)
  double max_speed_vertical = 3.0;            // [m/s]
  double max_accel_horizontal = 8.0;          // [m/s^2] acceleration setpoint limit
  double max_accel_vertical = 6.0;            // [m/s^2]
  Vec3 integral_limit = Vec3(2.0, 2.0, 4.0);  // [m/s^2] anti-windup clamp of the integral term
  double max_tilt = 0.6;                      // [rad] between the thrust vector and the world's z
  double min_thrust_fraction = 0.1;           // of the weight: the thrust never drops below this

  // Throws std::invalid_argument naming the field.
  void Validate() const;
};

// Desired flat outputs from the trajectory (world frame).
struct PositionSetpoint {
  Vec3 p_W = Vec3::Zero();  // [m]
  Vec3 v_W = Vec3::Zero();  // [m/s] feed-forward
  Vec3 a_W = Vec3::Zero();  // [m/s^2] feed-forward
  double yaw = 0.0;         // [rad] about the world's z, 0 along +x
};

struct AttitudeSetpoint {
  Quat q_WB = Quat::Identity();  // desired attitude
  double thrust = 0.0;           // collective thrust [N], along the body's z
  Vec3 a_W = Vec3::Zero();       // the acceleration it asks for [m/s^2] (for telemetry)
  Vec3 v_W = Vec3::Zero();       // the velocity setpoint [m/s] (for telemetry)
};

class PositionController {
 public:
  PositionController(const PositionControlParams& params, double mass);

  // One step of dt [s]. Returns false (and leaves `out` untouched, the integral unchanged) when
  // an input is not finite or dt is not positive; never throws.
  bool Update(const PositionSetpoint& setpoint, const Vec3& p_W, const Vec3& v_W, const Quat& q_WB,
              double dt, AttitudeSetpoint* out);

  void Reset() { integral_.setZero(); }

 private:
  PositionControlParams params_;
  double mass_;
  Vec3 integral_ = Vec3::Zero();  // [m/s^2]
};

// Limits the horizontal and vertical parts of v separately (gravity acts only on the vertical).
Vec3 LimitSplit(const Vec3& v, double horizontal, double vertical);

}  // namespace aerobox
