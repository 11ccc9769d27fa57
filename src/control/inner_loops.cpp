#include "control/inner_loops.h"

#include <limits>

namespace aerobox {

void InnerLoopParams::Validate() const {
  attitude.Validate();
  rate.Validate();
}

const char* ToString(CommandLevel level) {
  switch (level) {
    case CommandLevel::kRotorThrusts:
      return "rotor thrusts";
    case CommandLevel::kThrustMoment:
      return "thrust and moments";
    case CommandLevel::kThrustRates:
      return "thrust and body rates";
    case CommandLevel::kThrustAttitude:
      return "thrust and attitude";
  }
  return "?";
}

InnerLoops::InnerLoops(const InnerLoopParams& params, const QuadParams& vehicle)
    : attitude_(params.attitude),
      rate_(params.rate, vehicle.inertia),
      mixer_(vehicle),
      allocation_(AllocationMatrix(vehicle)),
      min_rotor_thrust_(vehicle.MinRotorThrust()),
      max_rotor_thrust_(vehicle.MaxRotorThrust()) {
  params.Validate();
}

bool InnerLoops::Run(const ControlCommand& command, const State& state, double dt,
                     InnerOutput* out) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  *out = InnerOutput();
  bool ok = true;
  switch (command.level) {
    case CommandLevel::kRotorThrusts: {
      if (!command.rotor_thrusts.allFinite()) {
        ok = false;
        break;
      }
      // only the rotors' limits: what the allocation makes of them is reported as the moment
      out->mixer.thrusts =
          command.rotor_thrusts.cwiseMax(min_rotor_thrust_).cwiseMin(max_rotor_thrust_);
      const Vec4 wrench = allocation_ * out->mixer.thrusts;
      out->thrust = wrench[0];
      out->moment_B = wrench.tail<3>();
      out->rate_setpoint_B.setConstant(kNaN);
      saturated_ = (out->mixer.thrusts - command.rotor_thrusts).cwiseAbs().maxCoeff() > 1e-12;
      return true;
    }
    case CommandLevel::kThrustAttitude:
      ok = attitude_.Update(state.q_WB, command.q_WB, &out->rate_setpoint_B) &&
           command.rate_B.allFinite();
      out->rate_setpoint_B += command.rate_B;  // the command's feed-forward
      break;
    case CommandLevel::kThrustRates:
      out->rate_setpoint_B = command.rate_B;
      break;
    case CommandLevel::kThrustMoment:
      out->rate_setpoint_B.setConstant(kNaN);
      out->moment_B = command.moment_B;
      break;
  }
  if (ok && command.level != CommandLevel::kThrustMoment) {
    ok = rate_.Update(out->rate_setpoint_B, state.w_B, dt, saturated_, &out->moment_B);
  }
  out->thrust = command.thrust;
  ok = ok && mixer_.Mix(command.thrust, out->moment_B, &out->mixer);
  if (!ok) {
    out->mixer = MixerOutput();  // zero thrust: the caller decides what a failure means
    return false;
  }
  saturated_ = out->mixer.saturated();
  return true;
}

}  // namespace aerobox
