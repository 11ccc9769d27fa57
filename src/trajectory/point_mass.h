// The time-optimal point mass through waypoints: a reference for how fast any vehicle can fly
// a path. A double integrator with |v| <= max_speed and |a| <= max_accel (Euclidean norms),
// from rest at the first waypoint, through every waypoint in order, to rest at the last; the
// curve between waypoints is free (it may cut corners), the times at the waypoints are free.
// Solved by direct multiple shooting with Ipopt: each segment has `intervals` pieces of
// constant acceleration and its own duration. The problem is not convex (the durations
// multiply the controls); Ipopt returns the local optimum nearest to stopping at every
// waypoint, which is where it starts.
#pragma once

#include <string>
#include <vector>

#include "common/types.h"

namespace aerobox {

struct PointMassParams {
  double max_speed = 8.0;   // [m/s] > 0
  double max_accel = 10.0;  // [m/s^2] > 0
  int intervals = 16;       // pieces of constant acceleration per segment, >= 2
  int max_iterations = 500;
};

struct PointMassResult {
  bool solved = false;                  // Ipopt converged (to its tolerance or an acceptable one)
  std::string message;                  // Ipopt's status, in words
  double time = 0.0;                    // [s] total; valid when solved
  std::vector<double> segment_times;    // [s] one per segment
  std::vector<Vec3> waypoint_velocity;  // [m/s] at each waypoint (zero at both ends)
};

// Throws std::invalid_argument for fewer than 2 waypoints, repeated consecutive waypoints,
// non-finite numbers or parameters out of range.
PointMassResult MinimumTimePointMass(const std::vector<Vec3>& waypoints,
                                     const PointMassParams& params = {});

}  // namespace aerobox
