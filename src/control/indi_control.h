// Incremental nonlinear dynamic inversion (INDI) on a flatness-based outer loop, after Tal and
// Karaman, "Accurate tracking of aggressive quadrotor trajectories using incremental nonlinear
// dynamic inversion and differential flatness" (IEEE TCST 2021). Instead of modelling every
// force and moment, it measures what the vehicle does and changes only the difference:
// - the thrust: the filtered thrust vector the rotors give now, plus the mass times the
//   difference between the acceleration the trajectory asks (feed-forward and PD feedback) and
//   the filtered measured acceleration; wind and drag are in the measurement, so they are met
//   without a model;
// - the moments: the filtered moments the rotors give now, plus the inertia times the
//   difference between the angular acceleration the attitude law asks (Lee et al.'s, as the
//   se3 controller's) and the filtered measured one (the gyroscope, differenced).
// Every measurement passes the same second-order low-pass, so they stay in step. With sensors
// on, the acceleration is the IMU's (its specific force less the estimated bias) and the rates
// the estimate's gyroscope; with sensors off, the physics' own (ground truth). The rotors'
// thrusts are measured as a real vehicle measures its rotor speeds (through the thrust
// coefficient). Command: thrust and moments.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/schema.h"
#include "control/controller.h"
#include "control/low_pass.h"
#include "control/se3_control.h"
#include "vehicle/quad_params.h"

namespace aerobox {

struct IndiParams {
  // the outer loop's PD on the position and velocity errors, and the attitude law's gains (per
  // unit mass and inertia, as se3's)
  Se3Params gains;
  // [Hz] the measurements' second-order low-pass (Tal and Karaman: about the rotors' bandwidth)
  double filter_cutoff = 30.0;

  void Describe(Archive& a);  // [controller] with kind = "indi" (common/schema.h)
  // Throws std::invalid_argument naming the key (the cutoff must stay below half the rate).
  void Validate(double rate) const;
};

class IndiController : public Controller {
 public:
  // `rate` [Hz]: how often Update runs (the filters' sampling rate).
  IndiController(const IndiParams& params, const QuadParams& vehicle, double rate);

  void Sense(const Surroundings& now) override { now_ = now; }
  ControlStatus Update(double t, const State& state, const FlatOutput& setpoint,
                       ControlCommand* command) override;

  // ax_f, ay_f, az_f [m/s^2]: the filtered measured acceleration; indi_fx, indi_fy, indi_fz [N]:
  // the force the increment met (the filtered measured acceleration times the mass, less the
  // filtered thrust and gravity); imu [-]: 1 when the measurements came from the IMU, 0 from
  // the ground truth.
  std::vector<std::string> ReportColumns() const override;
  void Report(std::vector<double>* values) const override;

 private:
  IndiParams params_;
  double mass_;
  Vec3 inertia_;
  Mat4 allocation_;
  double period_;
  Surroundings now_;
  LowPass2<Vec3> acceleration_, thrust_, rates_, moments_;
  std::optional<Vec3> last_rates_;  // filtered [rad/s], the step before
  Vec3 external_W_ = Vec3::Zero();  // [N]
};

}  // namespace aerobox
