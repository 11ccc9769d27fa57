#include "control/cascade.h"

#include <stdexcept>

namespace aerobox {

void CascadeParams::Validate() const {
  position.Validate();
  attitude.Validate();
  rate.Validate();
  if (!(step > 0) || outer_divider < 1) {
    throw std::invalid_argument("CascadeParams: step must be > 0 and outer_divider >= 1");
  }
}

CascadeController::CascadeController(const CascadeParams& params, const QuadParams& vehicle)
    : params_(params),
      position_(params.position, vehicle.mass),
      attitude_(params.attitude),
      rate_(params.rate, vehicle.inertia),
      mixer_(vehicle) {
  params_.Validate();
  last_attitude_.thrust = vehicle.mass * kGravity;
}

bool CascadeController::Update(const PositionSetpoint& setpoint, const State& state,
                               CascadeOutput* out) {
  *out = CascadeOutput();
  out->outer_step = steps_ % params_.outer_divider == 0;
  ++steps_;
  const double outer_dt = params_.step * params_.outer_divider;
  bool ok = true;
  if (out->outer_step) {
    ok = position_.Update(setpoint, state.p_W, state.v_W, state.q_WB, outer_dt, &last_attitude_);
  }
  out->attitude = last_attitude_;
  ok = ok && attitude_.Update(state.q_WB, last_attitude_.q_WB, &out->rate_setpoint_B);
  ok =
      ok && rate_.Update(out->rate_setpoint_B, state.w_B, params_.step, saturated_, &out->torque_B);
  ok = ok && mixer_.Mix(last_attitude_.thrust, out->torque_B, &out->mixer);
  if (!ok) {
    out->mixer = MixerOutput();  // zero thrust: the caller decides what a failure means
    return false;
  }
  saturated_ = out->mixer.saturated();
  return true;
}

}  // namespace aerobox
