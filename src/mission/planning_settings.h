// What a scenario's [planner] and [trajectory] tables set: clearances, RRT*'s parameters and
// the trajectory generator's.
#pragma once

#include <limits>
#include <string>

#include "common/schema.h"
#include "geometry/collision_world.h"
#include "planning/lattice_planner.h"
#include "planning/rrt_star.h"
#include "trajectory/baselines.h"
#include "trajectory/generators.h"
#include "trajectory/trajectory_generator.h"

namespace aerobox {

// The app's planner defaults differ from RrtStarParams' in one way: they stop on iteration
// counts, so that the same seed gives the same path on any machine; the time budget is only a
// safety cap.
struct PlanningSettings {
  // What the planner keeps from obstacles and the bounds [m], beyond the vehicle's own box
  // (FlightSetup::PlannerCollision).
  double clearance = 0.10;
  RrtStarParams rrt = [] {
    RrtStarParams p;
    p.max_iterations = 4000;          // after the first solution
    p.max_search_iterations = 20000;  // before it; then the lattice takes over
    p.time_budget = 10.0;
    return p;
  }();
  // "rrt_star", "lattice", or "auto": the lattice for maps wider than 200 m (a city), where
  // one query crosses hundreds of metres, RRT* otherwise
  std::string planner = "auto";
  // planner "waypoints": the path start, these, goal [m]
  std::vector<Vec3> waypoints;
  // a registered planner's own parameters ([planner] keys beyond the built-ins')
  PluginParameters planner_params;
  // when RRT* finds no path, a fine lattice over the map searches it exhaustively
  bool lattice_fallback = true;
  LatticeParams lattice;  // altitudes relative to the map's floor: see PlanFlight
  // min-time by default: the vehicle's limits (filled from QuadParams by TrajectoryAlong) and
  // the margins decide; max_speed and max_accel are caps only when a scenario sets them. With
  // objective "snap" and no caps, the snap objective's 2 m/s and 2 m/s^2.
  TrajectoryParams trajectory = [] {
    TrajectoryParams p;
    p.objective = TimeObjective::kMinTime;
    p.max_speed = std::numeric_limits<double>::infinity();
    p.max_accel = std::numeric_limits<double>::infinity();
    return p;
  }();
  // a name in TrajectoryGenerators(): minsnap (ours), a baseline on min-snap's waypoints and
  // times (trajectory/baselines.h), or "given" with the samples below
  std::string trajectory_method = "minsnap";
  std::vector<TrajectorySample> given_trajectory;  // [trajectory] file, for method "given"
  // What the trajectory keeps from obstacles [m]: half the planner's, so that the corridors
  // around the planner's path have room to bend in.
  double trajectory_clearance = 0.05;

  // [planner]'s keys but kind and waypoints (read by the registry's names and as a list of
  // points), RRT*'s among them (common/schema.h). lattice_spacing sets both of the lattice's
  // spacings: the caller copies it to vertical_spacing.
  void DescribePlanner(Archive& a);
  // [trajectory]'s keys but method and file, the generator's among them.
  void DescribeTrajectory(Archive& a);
};

}  // namespace aerobox
