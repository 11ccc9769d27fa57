#include "disturbance/aero.h"

namespace aerobox {

void AeroParams::Describe(Archive& a) {
  a.Boolean({"body_drag", "", "the body's drag in the air (a scenario's drag = true sets both)"},
            &body_drag);
  a.Boolean({"rotor_drag", "", "the rotors' induced drag, which also damps rotation"}, &rotor_drag);
}

Wrench AerodynamicWrench(const QuadParams& vehicle, const AeroParams& params, const State& state,
                         const Vec4& rotor_thrusts, const Vec3& wind_W) {
  const Mat3 R_WB = state.q_WB.toRotationMatrix();
  const Vec3 air_B = R_WB.transpose() * (state.v_W - wind_W);
  Vec3 force_B = Vec3::Zero();
  Vec3 torque_B = Vec3::Zero();
  if (params.body_drag) {
    force_B -= air_B.norm() * vehicle.body_drag.cwiseProduct(air_B);
  }
  if (params.rotor_drag) {
    for (int i = 0; i < kNumRotors; ++i) {
      const Vec3& r = vehicle.rotor_positions_B[i];
      const Vec3 air_i = air_B + state.w_B.cross(r);
      const Vec3 f = -rotor_thrusts[i] * vehicle.rotor_drag.cwiseProduct(air_i);
      force_B += f;
      torque_B += r.cross(f);
    }
  }
  return {R_WB * force_B, R_WB * torque_B};
}

}  // namespace aerobox
