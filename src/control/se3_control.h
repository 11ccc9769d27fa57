// Geometric tracking control on SE(3) (Lee, Leok and McClamroch 2010, "Geometric tracking
// control of a quadrotor UAV on SE(3)"), in ENU with z up: a force from the position and
// velocity errors plus the feed-forward acceleration gives the collective thrust and the
// desired body z; the attitude error on SO(3) and the body-rate error give the moments. The
// desired body rates and their derivative come from the trajectory's jerk and snap by
// differential flatness (Mellinger and Kumar 2011). Command: thrust and moments.
#pragma once

#include <optional>

#include "control/controller.h"
#include "vehicle/quad_params.h"

namespace aerobox {

struct Se3Params {
  // Gains per unit mass and per unit inertia, so that they carry over between vehicles:
  // force = m (-position_gain e_x - velocity_gain e_v + ...), moment = J (-attitude_gain e_R -
  // rate_gain e_W) + ...
  Vec3 position_gain = Vec3(8.0, 8.0, 12.0);      // [1/s^2]
  Vec3 velocity_gain = Vec3(5.0, 5.0, 7.0);       // [1/s]
  Vec3 attitude_gain = Vec3(300.0, 300.0, 80.0);  // [1/s^2]
  Vec3 rate_gain = Vec3(30.0, 30.0, 15.0);        // [1/s]
  // The position error's integral, so that a steady force (a mean wind) leaves no steady error,
  // and its clamp [m/s^2] (anti-windup); it grows only while the velocity error is under
  // 0.2 m/s. Off by default: it slows every transient (the Crazyflie released 7 cm off holds
  // within 10 mm after 3 s instead of 0.3 mm, a 1 m step overshoots 5 % instead of 0.03 %); a
  // scenario with wind turns it on (FollowTheAir, mission/setup.h).
  // 4, 4, 6 puts the error's poles at -2, -2, -1 1/s across and -4.7, -1.3, -1 1/s along z;
  // Routh: stable while it is below position_gain * velocity_gain. The disturbance observer,
  // which meets the force itself, flies without it (control/controllers.h).
  Vec3 position_integral = Vec3::Zero();  // [1/s^3]
  double integral_limit = 4.0;            // [m/s^2]
  double max_tilt = 0.6;  // [rad] between the force and the world's z (as the cascade's)

  // Throws std::invalid_argument naming the field.
  void Validate() const;
};

// The pieces of the law that other controllers share (control/indi_control.h):
// - LimitTilt: `a` [m/s^2] with its vertical part at least 0.1 g and its horizontal part shrunk
//   so that it leans at most `max_tilt` [rad] from the world's z;
// - FlatAttitude: for a force per unit mass `a` (world, gravity included) and the setpoint's yaw,
//   jerk and snap, the desired attitude, its body rates and their derivative;
// - AttitudeAcceleration: Lee et al.'s angular acceleration [rad/s^2] toward `target` from the
//   attitude `r` and the body rates `w_B`, and the attitude error e_R.
struct AttitudeTarget {
  Mat3 r_d = Mat3::Identity();
  Vec3 w_d = Vec3::Zero();      // [rad/s]
  Vec3 w_dot_d = Vec3::Zero();  // [rad/s^2]
};
Vec3 LimitTilt(Vec3 a, double max_tilt);
AttitudeTarget FlatAttitude(const Vec3& a, const FlatOutput& setpoint);
Vec3 AttitudeAcceleration(const Se3Params& gains, const Mat3& r, const Vec3& w_B,
                          const AttitudeTarget& target, Vec3* e_R = nullptr);

class Se3Controller : public Controller {
 public:
  Se3Controller(const Se3Params& params, const QuadParams& vehicle);

  ControlStatus Update(double t, const State& state, const FlatOutput& setpoint,
                       ControlCommand* command) override;

  // ex_R, ey_R, ez_R [-]: the attitude error vector e_R of Lee et al.;
  // wx_d, wy_d, wz_d [rad/s]: the desired body rates from the trajectory's jerk.
  std::vector<std::string> ReportColumns() const override;
  void Report(std::vector<double>* values) const override;

 private:
  Se3Params params_;
  double mass_;
  Vec3 inertia_;
  Vec3 last_e_R_ = Vec3::Zero();
  Vec3 last_w_d_ = Vec3::Zero();
  Vec3 integral_ = Vec3::Zero();  // [m/s^2] the integral term, clamped
  std::optional<double> last_t_;  // [s] of the last Update
};

}  // namespace aerobox
