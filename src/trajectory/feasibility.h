// What a vehicle can fly, checked along a trajectory by differential flatness (Mellinger and
// Kumar 2011): from acceleration, jerk and snap at constant yaw follow the collective thrust,
// the tilt, the body rates, the angular accelerations and, through the allocation matrix, each
// rotor's thrust, with drag's share when the limits carry a drag model. No vehicle types here:
// the mission fills FlatnessLimits from QuadParams.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "common/drag.h"
#include "trajectory/polynomial.h"

namespace aerobox {

struct FlatnessLimits {
  double mass = 0.0;               // [kg]
  Vec3 inertia = Vec3::Zero();     // principal moments [kg m^2]
  Mat4 allocation = Mat4::Zero();  // [thrust N; moments N m] = allocation * rotor thrusts [N]
  double min_rotor_thrust = 0.0;   // what the trajectory may ask of each rotor [N] (margins in)
  double max_rotor_thrust = 0.0;
  double max_tilt = 0.5;            // [rad] between the thrust and the world's z
  double max_rate = 6.0;            // [rad/s] body rate
  double max_speed = 8.0;           // [m/s]
  double max_vertical_speed = 3.0;  // [m/s]
  double max_accel = std::numeric_limits<double>::infinity();  // [m/s^2], an extra cap
  double yaw = 0.0;                                            // held along the trajectory [rad]
  // Drag the thrust must also overcome, in the wind expected (none: the ideal vehicle)
  DragModel drag;
  Vec3 wind = Vec3::Zero();  // [m/s]

  bool valid() const { return mass > 0; }
};

// The worst point of a trajectory against the limits: `ratio` <= 1 is feasible; `scale` is the
// factor by which time must stretch (> 1) or may shrink (< 1) for that limit to be met exactly,
// each limit with its order in time (speed and rates 1, accelerations, tilt and the rotors' swing
// about hover 2).
struct FeasibilityCheck {
  double ratio = 0.0;
  double scale = 0.0;
  double t = 0.0;     // [s] where
  std::string limit;  // "rotor 2 thrust", "tilt", "speed", ...
};

// Checks samples every `dt` seconds in [t0, t1] (the whole trajectory by default).
FeasibilityCheck CheckFeasibility(const PiecewiseTrajectory& trajectory,
                                  const FlatnessLimits& limits, double dt, double t0 = 0.0,
                                  double t1 = std::numeric_limits<double>::infinity());

// The check for each segment on its own.
std::vector<FeasibilityCheck> CheckSegments(const PiecewiseTrajectory& trajectory,
                                            const FlatnessLimits& limits, double dt);

}  // namespace aerobox
