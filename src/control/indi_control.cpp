#include "control/indi_control.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "common/number_format.h"
#include "control/disturbance_observer.h"

namespace aerobox {

void IndiParams::Describe(Archive& a) {
  a.Vector({"indi_position_gain", "1/s^2", "indi: on the position error"}, &gains.position_gain, 0,
           1e5);
  a.Vector({"indi_velocity_gain", "1/s", "indi: on the velocity error"}, &gains.velocity_gain, 0,
           1e5);
  a.Vector({"indi_attitude_gain", "1/s^2", "indi: on the attitude error"}, &gains.attitude_gain, 0,
           1e5);
  a.Vector({"indi_rate_gain", "1/s", "indi: on the body-rate error"}, &gains.rate_gain, 0, 1e5);
  a.Number({"indi_filter_cutoff", "Hz",
            "indi: the measurements' second-order low-pass (acceleration, rates, rotor thrusts; "
            "Tal and Karaman: near the rotors' bandwidth), below half the rate"},
           &filter_cutoff, 0.1, 1000);
}

void IndiParams::Validate(double rate) const {
  gains.Validate();
  if (!(filter_cutoff > 0 && filter_cutoff < 0.5 * rate)) {
    throw std::invalid_argument("controller.indi_filter_cutoff: " + FormatNumber(filter_cutoff) +
                                " Hz must lie below half the controller's rate (" +
                                FormatNumber(0.5 * rate) + " Hz)");
  }
}

IndiController::IndiController(const IndiParams& params, const QuadParams& vehicle, double rate)
    : params_(params),
      mass_(vehicle.mass),
      inertia_(vehicle.inertia),
      allocation_(AllocationMatrix(vehicle)),
      period_(1.0 / rate),
      acceleration_(params.filter_cutoff, rate),
      thrust_(params.filter_cutoff, rate),
      rates_(params.filter_cutoff, rate),
      moments_(params.filter_cutoff, rate) {
  params_.Validate(rate);
}

ControlStatus IndiController::Update(double, const State& state, const FlatOutput& setpoint,
                                     ControlCommand* command) {
  if (!setpoint.AllFinite() || !state.AllFinite() || !now_.acceleration_W.allFinite() ||
      !now_.rotor_thrusts.allFinite()) {
    return ControlStatus::NonFinite();
  }
  const Mat3 r = state.q_WB.normalized().toRotationMatrix();
  // the measurements, filtered alike: acceleration, the rotors' thrust (per unit mass, in the
  // world) and moments, the body rates and their change
  const Vec4 wrench = allocation_ * now_.rotor_thrusts;  // thrust [N], moments [N m]
  const Vec3& a_f = acceleration_.Update(now_.acceleration_W);
  const Vec3& thrust_f = thrust_.Update(r.col(2) * wrench(0) / mass_);
  const Vec3& moments_f = moments_.Update(wrench.tail<3>());
  const Vec3 w_f = rates_.Update(state.w_B);
  const Vec3 w_dot_f = last_rates_ ? Vec3((w_f - *last_rates_) / period_) : Vec3::Zero();
  last_rates_ = w_f;
  external_W_ = ExternalForce(mass_, a_f, mass_ * thrust_f);

  // the acceleration the trajectory asks, and the increment that gets it: what the thrust
  // gives now, plus what the vehicle lacks
  const Se3Params& g = params_.gains;
  const Vec3 a_ref = setpoint.a_W - g.position_gain.cwiseProduct(state.p_W - setpoint.p_W) -
                     g.velocity_gain.cwiseProduct(state.v_W - setpoint.v_W);
  const Vec3 f = LimitTilt(thrust_f + a_ref - a_f, g.max_tilt);
  command->thrust = std::max(0.0, mass_ * f.dot(r.col(2)));

  // the attitude law's angular acceleration, and the increment on the moments the rotors give
  const AttitudeTarget target = FlatAttitude(f, setpoint);
  const Vec3 alpha = AttitudeAcceleration(g, r, state.w_B, target);
  command->level = CommandLevel::kThrustMoment;
  command->moment_B = moments_f + inertia_.cwiseProduct(alpha - w_dot_f);
  return command->moment_B.allFinite() && std::isfinite(command->thrust)
             ? ControlStatus::Ok()
             : ControlStatus::NonFinite();
}

std::vector<std::string> IndiController::ReportColumns() const {
  return {"ax_f", "ay_f", "az_f", "indi_fx", "indi_fy", "indi_fz", "imu"};
}

void IndiController::Report(std::vector<double>* values) const {
  const Vec3 a = acceleration_.started() ? acceleration_.value() : Vec3::Zero();
  *values = {
      a.x(), a.y(), a.z(), external_W_.x(), external_W_.y(), external_W_.z(), now_.imu ? 1.0 : 0.0};
}

}  // namespace aerobox
