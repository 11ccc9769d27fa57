// The planner seam: a planner sees the world only through its validity functions and the
// sampling bounds, and answers a start-goal query with a status and a path. The built-ins
// (rrt_star, lattice, waypoints) are ordinary implementations, registered by name; a user's
// planner is one more.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/registry.h"
#include "planning/plan_result.h"
#include "planning/validity.h"

namespace aerobox {

class Planner {
 public:
  virtual ~Planner() = default;
  // A collision-free path from start to goal [m], or a status saying why there is none. Never
  // throws for a problem without a solution.
  virtual PlanResult Plan(const Vec3& start, const Vec3& goal) = 0;
};

// What a planner is made from.
struct PlannerContext {
  Aabb bounds;        // where the vehicle's centre may be [m]
  Validity validity;  // what is free
  std::uint64_t seed = 1;
};

// Which planner, with its own parameters: an RrtStarParams for "rrt_star"
// (planning/rrt_star.h), a LatticeParams for "lattice" (planning/lattice_planner.h), a
// WaypointsParams for "waypoints", a registered planner's own type (set by its [planner] keys).
// Empty params: the defaults the kind registered, else its type's defaults.
struct PlannerConfig {
  std::string kind = "rrt_star";  // a name in Planners()
  PluginParameters params;
};

// The "waypoints" planner's parameters.
struct WaypointsParams {
  std::vector<Vec3> points;  // [m] the path goes start, these, goal, each leg checked
};

using PlannerFactory =
    std::function<std::unique_ptr<Planner>(const PlannerConfig&, const PlannerContext&)>;

// A path given whole (the waypoints planner, a user's planner), checked point by point and leg
// by leg: kSolved with the path and its length, or kPathBlocked with the first point or leg that
// is not free (stats.blocked_leg: the leg's end, 0 is the start) and the first position along it
// that is not free (stats.blocked_point, exact to a micrometre along a metre of leg).
PlanResult CheckGivenPath(std::vector<Vec3> path, const Validity& validity);

// The registry, with "rrt_star", "lattice" and "waypoints" in it.
Registry<PlannerFactory>& Planners();

// The planner `config.kind` names; throws std::invalid_argument for an unknown kind.
std::unique_ptr<Planner> MakePlanner(const PlannerConfig& config, const PlannerContext& context);

}  // namespace aerobox
