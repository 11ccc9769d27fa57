// The trajectory generators our users know, as baselines beside minimum snap: each takes the
// same waypoints and segment durations and returns a PiecewiseTrajectory (degree-7 storage;
// lower degrees leave the top coefficients zero). None of them looks at obstacles.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "trajectory/polynomial.h"

namespace aerobox {

enum class TrajectoryMethod {
  kMinSnap,     // ours: minimum snap with corridors (Ipopt), collision-aware (GenerateTrajectory)
  kQuintic,     // each segment alone, position, velocity and acceleration fixed at both ends
  kCubic,       // one global cubic spline, velocity and acceleration continuous
  kSepticFull,  // degree 7, derivatives 1-6 continuous, rest at both ends: one square system
};

// "minsnap", "quintic", "cubic", "septic-full".
const char* ToString(TrajectoryMethod method);
std::optional<TrajectoryMethod> ParseTrajectoryMethod(std::string_view name);

// Quintic segments, each solved alone. At the ends the vehicle rests; at an interior waypoint
// the velocity is the mean of the two segments' average velocities, and the acceleration is
// their difference divided by the mean of the two durations (a finite difference of the
// average velocities). Jerk jumps at waypoints.
PiecewiseTrajectory QuinticTrajectory(const std::vector<Vec3>& waypoints,
                                      const std::vector<double>& durations);

// The clamped cubic spline: zero velocity at both ends, velocity and acceleration continuous at
// interior waypoints (the minimum of the integrated squared acceleration with those ends). One
// tridiagonal system for the interior velocities.
PiecewiseTrajectory CubicSplineTrajectory(const std::vector<Vec3>& waypoints,
                                          const std::vector<double>& durations);

// Degree-7 segments through the waypoints with derivatives 1 to 6 continuous at interior
// waypoints and velocity, acceleration and jerk zero at both ends: 8 n equations in the 8 n
// coefficients, solved as one sparse square system.
PiecewiseTrajectory SepticFullTrajectory(const std::vector<Vec3>& waypoints,
                                         const std::vector<double>& durations);

// The baseline `method` (not kMinSnap, which needs the world: GenerateTrajectory).
PiecewiseTrajectory BaselineTrajectory(TrajectoryMethod method, const std::vector<Vec3>& waypoints,
                                       const std::vector<double>& durations);

}  // namespace aerobox
