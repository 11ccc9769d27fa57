#include "control/mixer.h"

#include <algorithm>
#include <cmath>

namespace aerobox {
namespace {

// The largest s in [0, 1] with base + s * direction inside [min, max] on every rotor (base is).
double LargestFit(const Vec4& base, const Vec4& direction, double min, double max) {
  double s = 1.0;
  for (int i = 0; i < kNumRotors; ++i) {
    if (direction[i] > 0) s = std::min(s, (max - base[i]) / direction[i]);
    if (direction[i] < 0) s = std::min(s, (min - base[i]) / direction[i]);
  }
  return std::max(0.0, s);
}

}  // namespace

Mixer::Mixer(const QuadParams& params)
    : inverse_(AllocationMatrix(params).inverse()),
      min_rotor_thrust_(params.MinRotorThrust()),
      max_rotor_thrust_(params.MaxRotorThrust()) {}

bool Mixer::Mix(double thrust, const Vec3& torque_B, MixerOutput* out) const {
  *out = MixerOutput();
  if (!std::isfinite(thrust) || !torque_B.allFinite()) return false;
  // thrust first: equal shares, within what four rotors give
  const double collective =
      std::clamp(thrust, kNumRotors * min_rotor_thrust_, kNumRotors * max_rotor_thrust_);
  const Vec4 base = inverse_.col(0) * collective;
  // then roll and pitch, scaled to fit
  const Vec4 roll_pitch = inverse_.col(1) * torque_B.x() + inverse_.col(2) * torque_B.y();
  out->roll_pitch_scale = LargestFit(base, roll_pitch, min_rotor_thrust_, max_rotor_thrust_);
  const Vec4 with_roll_pitch = base + out->roll_pitch_scale * roll_pitch;
  // yaw last, with what is left
  const Vec4 yaw = inverse_.col(3) * torque_B.z();
  out->yaw_scale = LargestFit(with_roll_pitch, yaw, min_rotor_thrust_, max_rotor_thrust_);
  out->thrusts = (with_roll_pitch + out->yaw_scale * yaw)
                     .cwiseMax(min_rotor_thrust_)
                     .cwiseMin(max_rotor_thrust_);
  return true;
}

}  // namespace aerobox
