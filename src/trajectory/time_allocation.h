// Segment durations: a trapezoidal speed profile per straight segment, then one uniform time
// scale that puts the solved trajectory exactly at its speed or acceleration limit.
#pragma once

#include <vector>

#include "trajectory/polynomial.h"

namespace aerobox {

// Time [s] to travel `length` [m] from rest to rest with speed <= max_speed [m/s] and
// acceleration <= max_accel [m/s^2] (a triangle when the segment is too short to cruise).
double TrapezoidTime(double length, double max_speed, double max_accel);

// TrapezoidTime of each segment of the polyline.
std::vector<double> TrapezoidDurations(const std::vector<Vec3>& waypoints, double max_speed,
                                       double max_accel);

// Redistributes `durations` (their sum fixed) to lower the equality-constrained minimum-snap
// cost through `waypoints` (Mellinger and Kumar 2011, section IV: gradient descent on the time
// ratios, the gradient by finite differences of the closed-form solve). Trapezoidal times stop
// at every waypoint; these let the vehicle carry speed through them. `iterations` steps of
// projected gradient descent with backtracking; no segment drops below 5 % of its start.
std::vector<double> RefineDurations(const std::vector<Vec3>& waypoints,
                                    std::vector<double> durations, int iterations);

// Stretches or compresses time uniformly (the path in space stays the same) so that the
// largest sampled speed and acceleration (every `dt` seconds) reach their limits and do not
// exceed them. Scaling time by f divides speeds by f and accelerations by f^2. Returns f.
double ScaleToLimits(double max_speed, double max_accel, double dt,
                     PiecewiseTrajectory* trajectory);

}  // namespace aerobox
