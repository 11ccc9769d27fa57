// What every planner answers through the planner seam (planning/planner.h): a status, the path
// and the search's statistics. The seam's own types: the built-in planners include this header,
// not the other way round.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "common/types.h"

namespace aerobox {

enum class PlanStatus {
  kSolved,
  kNoPathWithinBudget,  // no path found before the time or iteration budget ran out
  kStartInvalid,
  kGoalInvalid,
  kPathBlocked,  // a given path (the waypoints planner) leaves free space
};
const char* ToString(PlanStatus status);

struct PlanStats {
  long iterations = 0;
  size_t nodes = 0;                        // in the tree at the end
  double time_to_first_solution = -1.0;    // [s]; -1 when none was found
  long iterations_to_first_solution = -1;  // -1 when none was found
  double first_cost = -1.0;                // [m] length of the first solution
  double tree_cost = -1.0;                 // [m] the tree's best path at the end
  double final_cost = -1.0;                // [m] after shortcutting and pruning
  double planning_time = 0.0;              // [s] including simplification
  // the wall-time budget, not an iteration count, ended the search: the result then depends on
  // the machine's speed and load, not on the seed alone
  bool time_capped = false;
  // a graph built before the queries (the lattice): its edges and build time [s]
  size_t edges = 0;
  double build_time = 0.0;
  int blocked_leg = -1;  // kPathBlocked: the first point or leg (ending there) not free
  // kPathBlocked: the first position along that leg (or that point) that is not free [m]
  Vec3 blocked_point = Vec3::Zero();
  // (time [s], tree path length [m]) each time the best path improved: the anytime curve
  std::vector<std::pair<double, double>> cost_history;
};

struct PlanResult {
  PlanStatus status = PlanStatus::kNoPathWithinBudget;
  std::vector<Vec3> path;  // start, waypoints..., goal when solved; empty otherwise
  PlanStats stats;
  // with RrtStarParams::record_tree: (new node, its parent then), in the order they were added
  // (rewiring changes some parents later; this is the tree as it grew)
  std::vector<std::pair<Vec3, Vec3>> tree;
};

}  // namespace aerobox
