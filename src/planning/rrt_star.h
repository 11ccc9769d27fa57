// RRT* (Karaman and Frazzoli 2011, "Sampling-based algorithms for optimal motion planning") with
// informed sampling once a solution exists (Gammell et al. 2014), then shortcutting and pruning
// of the returned path. Deterministic for a given seed and iteration count.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "common/schema.h"
#include "common/types.h"
#include "planning/plan_result.h"
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

// Plans from start to goal, sampling inside `bounds` [m]. Never throws for a problem that has no
// solution; throws std::invalid_argument for invalid parameters.
PlanResult PlanRrtStar(const Vec3& start, const Vec3& goal, const Aabb& bounds,
                       const Validity& validity, const RrtStarParams& params);

}  // namespace aerobox
