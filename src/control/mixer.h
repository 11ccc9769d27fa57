// Collective thrust and body torques -> four rotor thrusts, through the inverse of the
// allocation matrix (vehicle/quad_params.h). When the rotors cannot deliver all of it, thrust
// comes first, then roll and pitch, then yaw: each is scaled down as far as needed to keep
// every rotor within [min, max].
#pragma once

#include "common/types.h"
#include "vehicle/quad_params.h"

namespace aerobox {

struct MixerOutput {
  Vec4 thrusts = Vec4::Zero();    // [N], each within the vehicle's rotor limits
  double roll_pitch_scale = 1.0;  // fraction of the roll/pitch torque delivered
  double yaw_scale = 1.0;         // fraction of the yaw torque delivered
  bool saturated() const { return roll_pitch_scale < 1.0 || yaw_scale < 1.0; }
};

class Mixer {
 public:
  explicit Mixer(const QuadParams& params);

  // Never throws; non-finite inputs give zero thrust and return false.
  bool Mix(double thrust, const Vec3& torque_B, MixerOutput* out) const;

 private:
  Mat4 inverse_;  // rotor thrusts per [thrust, roll, pitch, yaw]
  double min_rotor_thrust_;
  double max_rotor_thrust_;
};

}  // namespace aerobox
