// PX4's multicopter cascade as a Controller: position P -> velocity PID -> thrust vector ->
// collective thrust and attitude (position_control.h), at the controller's rate. The attitude
// and rate loops and the mixer below it are aerobox's inner loops (inner_loops.h), at the
// physics rate, as on PX4 where they run faster than the position loop. The command carries
// the body rates the trajectory's jerk asks for, as a feed-forward to the attitude loop.
#pragma once

#include "control/controller.h"
#include "control/position_control.h"

namespace aerobox {

// Body rates [rad/s] that the trajectory's jerk (and yaw rate) turn the thrust axis at, in the
// body frame of `q_WB`: the feed-forward that lets the attitude loop keep up at speed.
Vec3 RateFeedForward(const FlatOutput& setpoint, const Quat& q_WB);

class CascadeController : public Controller {
 public:
  // `period` [s] between updates (the controller's rate); throws std::invalid_argument for bad
  // parameters.
  CascadeController(const PositionControlParams& params, double period, double mass);

  ControlStatus Update(double t, const State& state, const FlatOutput& setpoint,
                       ControlCommand* command) override;

  // vx_sp, vy_sp, vz_sp [m/s]: the velocity setpoint after the position loop;
  // ax_sp, ay_sp, az_sp [m/s^2]: the acceleration the velocity loop asks for (tilt-limited).
  std::vector<std::string> ReportColumns() const override;
  void Report(std::vector<double>* values) const override;

 private:
  PositionController position_;
  double period_;
  AttitudeSetpoint last_;
};

}  // namespace aerobox
