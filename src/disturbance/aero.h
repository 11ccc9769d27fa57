// Aerodynamic forces on the vehicle from its airspeed (its velocity minus the wind): body drag,
// quadratic per body axis, and rotor drag, linear in each rotor's airspeed and proportional to
// its thrust (RotorPy's lumped model; Faessler et al. 2018). The coefficients are the
// vehicle's (QuadParams::body_drag, rotor_drag).
#pragma once

#include "common/schema.h"
#include "common/state.h"
#include "common/types.h"
#include "vehicle/quad_params.h"

namespace aerobox {

struct AeroParams {
  bool body_drag = false;   // [aero] body_drag (or drag: both)
  bool rotor_drag = false;  // [aero] rotor_drag
  bool Enabled() const { return body_drag || rotor_drag; }
  void Describe(Archive& a);  // [aero] (common/schema.h)
};

struct Wrench {
  Vec3 force_W = Vec3::Zero();   // [N] at the body origin (its centre of mass)
  Vec3 torque_W = Vec3::Zero();  // [N m]
};

// The wrench on a vehicle in `state` whose rotors produce `rotor_thrusts` [N] in the wind
// wind_W [m/s]. Each rotor's airspeed includes w x r_i, so rotor drag also damps rotation.
Wrench AerodynamicWrench(const QuadParams& vehicle, const AeroParams& params, const State& state,
                         const Vec4& rotor_thrusts, const Vec3& wind_W);

}  // namespace aerobox
