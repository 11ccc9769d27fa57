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

// The same for a polyline whose straight legs are cut into pieces (collinear waypoints): each
// leg is one rest-to-rest trapezoid, and each piece gets the time that profile spends on it, so
// the pieces in the middle of a long leg cruise.
std::vector<double> TrapezoidDurationsAlongLegs(const std::vector<Vec3>& waypoints,
                                                double max_speed, double max_accel);
// The gradient of the closed-form minimum-snap cost with respect to the segment durations
// [cost / s], at the optimum `trajectory` (SolveMinSnapClosedForm's). The optimum's free
// derivatives at the waypoints stay optimal to first order (envelope theorem; the snap
// continuity rows are met by the unconstrained optimum, so their multipliers vanish), so
// d cost / d T_i is segment i's own cost derivative with its end derivatives held: O(n) for n
// segments, instead of n solves for finite differences.
std::vector<double> SnapCostGradient(const PiecewiseTrajectory& trajectory);

// Redistributes `durations` (their sum fixed) to lower the equality-constrained minimum-snap
// cost through `waypoints` (Mellinger and Kumar 2011, section IV: gradient descent on the time
// ratios; the gradient from SnapCostGradient). Trapezoidal times stop at every waypoint; these
// let the vehicle carry speed through them. `iterations` steps of projected gradient descent
// with backtracking; no segment drops below 5 % of its start. Each step costs a few closed-form
// solves, each linear in the number of segments.
// `gradient` selects SnapCostGradient or, as a reference, forward differences of the whole solve
// (one solve per segment).
enum class DurationGradient { kEnvelope, kFiniteDifferences };
std::vector<double> RefineDurations(const std::vector<Vec3>& waypoints,
                                    std::vector<double> durations, int iterations,
                                    DurationGradient gradient = DurationGradient::kEnvelope);

// Stretches or compresses time uniformly (the path in space stays the same) so that the
// largest sampled speed and acceleration (every `dt` seconds) reach their limits and do not
// exceed them. Scaling time by f divides speeds by f and accelerations by f^2. Returns f.
double ScaleToLimits(double max_speed, double max_accel, double dt,
                     PiecewiseTrajectory* trajectory);

}  // namespace aerobox
