// Ours against OMPL 1.5.2's RRT* on the same problems: the same collision world (state and
// exact motion checks), the same range, goal bias, rewiring rule and time budget, in one process.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "common/progress.h"
#include "geometry/collision_world.h"

namespace aerobox {

// One planner run's anytime record.
struct AnytimeRun {
  double time_to_first = -1.0;                     // [s]; -1: no solution
  std::vector<std::pair<double, double>> history;  // (time [s], path length [m])
  double simplified_cost = -1.0;                   // [m] after the planner's own simplifier
  long iterations = 0;                             // samples drawn in the budget

  // Best path length reached by time t [s]; +infinity when none.
  double CostAt(double t) const;
};

struct PlanningProblem {
  std::string name;
  Map map;
  Vec3 start;
  Vec3 goal;
};

// Our RRT* with informed sampling (as `aerobox plan` runs it, but on a time budget).
AnytimeRun RunOurs(const CollisionWorld& world, const PlanningProblem& problem, double seconds,
                   std::uint64_t seed);

// Whether this build has the OMPL reference (CMake option AEROBOX_WITH_OMPL).
bool HaveOmpl();
// OMPL's RRTstar, k-nearest, optionally with its informed sampling; simplified afterwards with
// OMPL's PathSimplifier (shortcuts and vertex reduction). Only when HaveOmpl().
AnytimeRun RunOmpl(const CollisionWorld& world, const PlanningProblem& problem, double seconds,
                   bool informed);

// Runs every problem `seeds` times with each planner for `seconds`, and prints one markdown
// table of medians and ratios (ours / OMPL) for time to first solution and cost at 0.2 s and at
// `seconds`. Progress goes to `progress`.
void ComparePlanners(const std::vector<PlanningProblem>& problems, int seeds, double seconds,
                     std::ostream& out, ProgressDisplay& progress);

}  // namespace aerobox
