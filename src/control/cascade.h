// The whole cascade at its loop rates: position and velocity every `outer_divider` steps,
// attitude, rates and mixer every step. Pure math: state in, rotor thrusts out.
#pragma once

#include "common/state.h"
#include "control/attitude_control.h"
#include "control/mixer.h"
#include "control/position_control.h"
#include "control/rate_control.h"

namespace aerobox {

struct CascadeParams {
  PositionControlParams position;
  AttitudeControlParams attitude;
  RateControlParams rate;
  double step = 0.001;    // [s] of the inner loops (the physics step)
  int outer_divider = 4;  // position loop every 4 steps: 250 Hz at a 1 ms step

  void Validate() const;
};

// Everything one step computed, for telemetry.
struct CascadeOutput {
  AttitudeSetpoint attitude;  // from the last outer-loop step
  Vec3 rate_setpoint_B = Vec3::Zero();
  Vec3 torque_B = Vec3::Zero();
  MixerOutput mixer;
  bool outer_step = false;  // whether the position loop ran in this step
};

class CascadeController {
 public:
  CascadeController(const CascadeParams& params, const QuadParams& vehicle);

  // One inner-loop step. Returns false when any stage rejected its input (non-finite state or
  // setpoint): `out` then commands zero thrust. Never throws.
  bool Update(const PositionSetpoint& setpoint, const State& state, CascadeOutput* out);

 private:
  CascadeParams params_;
  PositionController position_;
  AttitudeController attitude_;
  RateController rate_;
  Mixer mixer_;
  AttitudeSetpoint last_attitude_;
  bool saturated_ = false;
  long steps_ = 0;
};

}  // namespace aerobox
