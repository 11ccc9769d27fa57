// Drag per unit mass in the world frame, lumped for planning and feed-forward: linear in the
// airspeed (rotor drag at hover thrust) plus quadratic (body drag), one coefficient per world
// axis. The simulation applies the full model (disturbance/aero.h: body axes, each rotor's
// thrust and airspeed); near level flight this is its first-order picture.
#pragma once

#include "common/flat_output.h"
#include "common/types.h"

namespace aerobox {

struct DragModel {
  Vec3 linear = Vec3::Zero();     // [1/s]
  Vec3 quadratic = Vec3::Zero();  // [1/m]
  bool active() const { return linear.squaredNorm() + quadratic.squaredNorm() > 0; }
};

// The acceleration drag gives a vehicle moving at `air_W` [m/s] through the air (its velocity
// minus the wind) [m/s^2], and its time derivative under the acceleration a_W.
Vec3 DragAcceleration(const DragModel& drag, const Vec3& air_W);
Vec3 DragAccelerationRate(const DragModel& drag, const Vec3& air_W, const Vec3& a_W);

// The flat outputs the thrust must produce for the vehicle to follow `setpoint` in the wind
// wind_W [m/s]: acceleration and jerk less drag's share (Faessler, Franchi and Scaramuzza 2018:
// drag enters the flat outputs as a feed-forward).
FlatOutput CompensateDrag(const FlatOutput& setpoint, const DragModel& drag,
                          const Vec3& wind_W = Vec3::Zero());

}  // namespace aerobox
