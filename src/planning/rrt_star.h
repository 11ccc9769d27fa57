// RRT* (Karaman and Frazzoli 2011, "Sampling-based algorithms for optimal motion planning") with
// informed sampling once a solution exists (Gammell et al. 2014), then shortcutting and pruning
// of the returned path. Deterministic for a given seed and iteration count.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "common/schema.h"
#include "common/types.h"
#include "planning/validity.h"

namespace aerobox {

struct RrtStarParams {
  // Longest edge the tree grows in one step [m]; 0 picks 0.2 x the diagonal of the sampling
  // bounds (OMPL's default "range").
  double max_step = 0.0;
  // Probability of steering towards the goal instead of a random sample, in [0, 1).
  double goal_bias = 0.05;
  // Scales the rewiring neighbourhood: k = rewire_factor * 2^4 * e * (1 + 1/3) * log(n + 1)
  // nearest nodes (the k-nearest form of RRT*; >= 1 keeps asymptotic optimality). Must be > 0.
  double rewire_factor = 1.1;
  // Stop after this much wall time [s] (> 0) ...
  double time_budget = 1.0;
  // ... or after this many iterations once a first solution exists (0: no limit): the anytime
  // improvement. The search for the first solution is not cut short by it, so a narrow map is
  // not given up early; with an ample time budget the result depends only on the seed.
  long max_iterations = 0;
  // At most this many iterations without a solution (0: no limit, only the time budget): a
  // deterministic end for maps without a path.
  long max_search_iterations = 0;
  // Stop as soon as a first solution exists (then skip the anytime improvement).
  bool stop_at_first_solution = false;
  // Sample only where the path can still improve, once there is one.
  bool informed = true;
  // Random shortcut attempts on the returned path (0: return the tree's path as it is).
  int shortcut_attempts = 100;
  // Seeds the planner's own mt19937_64.
  std::uint64_t seed = 1;
  // Keep every edge as it was added (PlanResult::tree), to draw the tree growing.
  bool record_tree = false;

  // A scenario's [planner] keys of RRT* (common/schema.h).
  void Describe(Archive& a);
  // Throws std::invalid_argument naming the field and value.
  void Validate() const;
};

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

// Plans from start to goal, sampling inside `bounds` [m]. Never throws for a problem that has no
// solution; throws std::invalid_argument for invalid parameters.
PlanResult PlanRrtStar(const Vec3& start, const Vec3& goal, const Aabb& bounds,
                       const Validity& validity, const RrtStarParams& params);

}  // namespace aerobox
