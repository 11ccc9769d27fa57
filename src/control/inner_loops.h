// The loops aerobox runs below a controller's command, at the physics rate: attitude (for a
// thrust-and-attitude command), body rates (for thrust and rates), the mixer (for thrust and
// moments), or only the rotors' limits (for rotor thrusts). The cascade's own inner loops are
// these, so a command at any level flies as the cascade would with the same gains.
#pragma once

#include "control/attitude_control.h"
#include "control/controller.h"
#include "control/mixer.h"
#include "control/rate_control.h"
#include "vehicle/quad_params.h"

namespace aerobox {

struct InnerLoopParams {
  AttitudeControlParams attitude;
  RateControlParams rate;

  void Validate() const;
};

// What the inner loops asked of the stage below, for telemetry.
struct InnerOutput {
  double thrust = 0.0;                  // collective thrust asked of the mixer [N]
  Vec3 rate_setpoint_B = Vec3::Zero();  // [rad/s]; NaN when the command lies below rates
  Vec3 moment_B = Vec3::Zero();         // moments asked of the mixer [N m]
  MixerOutput mixer;                    // the rotor thrust commands [N]
};

class InnerLoops {
 public:
  // Throws std::invalid_argument for bad parameters.
  InnerLoops(const InnerLoopParams& params, const QuadParams& vehicle);

  // One physics step of dt [s]. Returns false (zero thrust in `out`) for non-finite input.
  // Never throws.
  bool Run(const ControlCommand& command, const State& state, double dt, InnerOutput* out);

 private:
  AttitudeController attitude_;
  RateController rate_;
  Mixer mixer_;
  Mat4 allocation_;
  double min_rotor_thrust_;
  double max_rotor_thrust_;
  bool saturated_ = false;  // the mixer could not deliver the last moment: the rate integral holds
};

}  // namespace aerobox
