// From a planner's path to a smooth, dynamically feasible, collision-free trajectory:
// trapezoidal time allocation, safe corridors, minimum snap with Ipopt, a uniform time scale
// to the speed and acceleration limits, and collision-aware refinement (Richter, Bry and Roy
// 2013: where the trajectory leaves free space, the path segment's midpoint becomes a waypoint).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "common/schema.h"
#include "trajectory/corridor.h"
#include "trajectory/feasibility.h"
#include "trajectory/min_snap.h"

namespace aerobox {

// How the segment times are chosen.
enum class TimeObjective {
  // trapezoidal times redistributed to lower the snap, then one uniform scale that puts the
  // trajectory at max_speed or max_accel
  kSnap,
  // as fast as the vehicle flies (MinTimeDurations): each segment's time is scaled until its
  // worst point meets the vehicle's limits (FlatnessLimits: rotor thrusts, tilt, rates, speed)
  kMinTime,
};
const char* ToString(TimeObjective objective);

struct TrajectoryParams {
  TimeObjective objective = TimeObjective::kSnap;
  // kSnap: the limits the trajectory is scaled to; kMinTime: extra caps (infinity: none)
  double max_speed = 2.0;  // [m/s] (a Tello does 8; tracking is tighter when slower)
  double max_accel = 2.0;  // [m/s^2]
  // kMinTime: the vehicle (mass, inertia, allocation, rotor range, top speed) and the margins
  // the trajectory leaves to the controller
  FlatnessLimits vehicle;
  double thrust_margin = 0.25;      // of each rotor's swing from hover to its limits
  double max_tilt = 0.5;            // [rad]
  double max_rate = 6.0;            // [rad/s] body rate
  double max_vertical_speed = 2.5;  // [m/s] (below the cascade's 3, for its feedback)
  // kMinTime, in wind: the wind beyond its mean that tilt and thrust are kept for, in turbulence
  // intensities (the gusts' peaks are added); the mission turns it into a smaller max_tilt and
  // rotor limit (mission/plan.h)
  double wind_reserve = 2.0;
  int time_iterations = 30;  // rounds of per-segment time scaling
  // kMinTime: straight segments longer than this are cut in pieces, so that the vehicle can
  // cruise along them at its top speed [m]
  double cruise_piece = 4.0;
  bool use_corridors = true;     // false: equality constraints only (closed form, no Ipopt)
  double corridor_growth = 1.0;  // how far a corridor may reach past its segment's box [m]
  // kept between the constrained samples and the corridor's faces [m]: more than the
  // trajectory bulges between samples, so the corridor holds everywhere, not only at samples
  double corridor_margin = 0.01;
  int samples_per_segment = 16;  // constrained samples per segment
  int max_refinements = 8;       // rounds of inserting midpoints where the trajectory collides
  double check_step = 0.01;      // [s] between samples of the collision check and the limits
  // gradient steps redistributing the trapezoidal times to lower the snap (0: keep them)
  int time_refinement_steps = 20;
  // when Ipopt fails on the corridors, try the closed form with collision-aware refinement
  // (generators.h: MinSnapWithFallback)
  bool closed_form_fallback = true;
  IpoptSettings ipopt;

  // A scenario's [trajectory] keys (common/schema.h).
  void Describe(Archive& a);
  // Throws std::invalid_argument naming the field and value.
  void Validate() const;
};

// The world as the trajectory generator sees it (vehicle-centre positions, no map types).
struct TrajectoryWorld {
  BoxFree box_free;
  std::function<bool(const Vec3&, const Vec3&)> segment_free;
};

enum class TrajectoryStatus {
  kSolved,
  kInfeasible,  // the optimiser found no trajectory inside the corridors
  kFailed,      // the optimiser failed for another reason (see message)
  kCollides,    // still collides after max_refinements rounds
};
const char* ToString(TrajectoryStatus status);

struct TrajectoryStats {
  int refinements = 0;  // midpoint insertions done
  int segments = 0;
  int solves = 0;              // closed-form solves of a continuation's time search
  double solve_time = 0.0;     // [s] wall time of the whole generation
  double duration = 0.0;       // [s]
  double max_speed = 0.0;      // [m/s], sampled
  double max_accel = 0.0;      // [m/s^2], sampled
  double snap_cost = 0.0;      // [m^2/s^7]
  std::string solver_message;  // Ipopt's last return status
  // Ipopt failed on the corridors and the closed form (refined, checked) is the result
  // (TrajectoryParams::closed_form_fallback); solver_message then says why Ipopt failed
  bool closed_form_fallback = false;
  // min-time: the limit the trajectory meets most closely, where and how closely
  FeasibilityCheck binding_limit;
};

struct TrajectoryResult {
  TrajectoryStatus status = TrajectoryStatus::kFailed;
  PiecewiseTrajectory trajectory;
  std::vector<Vec3> waypoints;                 // after splitting and refinement
  std::vector<std::optional<Aabb>> corridors;  // one per segment (nothing: bounds only)
  TrajectoryStats stats;
};

// The path must be collision-free (as RRT* returns it); its first and last points are where the
// trajectory starts and ends at rest.
TrajectoryResult GenerateTrajectory(const std::vector<Vec3>& path, const TrajectoryWorld& world,
                                    const TrajectoryParams& params);

// Where a trajectory that continues another starts: its position, velocity, acceleration and
// jerk at the switch.
struct StartState {
  Vec3 p_W = Vec3::Zero();
  Vec3 v_W = Vec3::Zero();
  Vec3 a_W = Vec3::Zero();
  Vec3 j_W = Vec3::Zero();
};

// A trajectory along `path` (path.front() is start.p_W) that starts in `start` and ends at rest,
// for replanning in flight: min-snap through the waypoints (closed form, no corridors: fast),
// its times from the vehicle's limits (params.vehicle with its margins; the snap objective's
// max_speed and max_accel otherwise), stretched segment by segment until it is feasible, and
// midpoints inserted where it leaves free space. The times are re-solved, never stretched
// uniformly after the solve, so the start state holds exactly.
TrajectoryResult ContinueTrajectory(const StartState& start, const std::vector<Vec3>& path,
                                    const TrajectoryWorld& world, const TrajectoryParams& params);

// The limits a kMinTime trajectory is held to: `params.vehicle` with the margins and caps.
FlatnessLimits EffectiveLimits(const TrajectoryParams& params);

// Fills result->stats' duration, sampled top speed and acceleration (every check_step) and snap
// cost from result->trajectory (left as they are when it is empty).
void MeasureTrajectory(const TrajectoryParams& params, TrajectoryResult* result);

// Where the trajectory, sampled every `step` seconds, first leaves free space: the time [s],
// or nothing when it stays free.
std::optional<double> FirstCollisionTime(const PiecewiseTrajectory& trajectory,
                                         const TrajectoryWorld& world, double step);

}  // namespace aerobox
