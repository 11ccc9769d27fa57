// Planning a flight set-up: the collision world, start and goal made usable, RRT*.
#pragma once

#include <string>
#include <utility>

#include "common/error.h"
#include "geometry/collision_world.h"
#include "mission/setup.h"
#include "planning/lattice_planner.h"
#include "planning/planner.h"
#include "trajectory/trajectory_generator.h"

namespace aerobox {

// Where a requested start or goal ended up. Points on the bounds or on the floor, and points
// within the clearance of an obstacle, are moved by the smallest amount that makes them usable.
struct Endpoint {
  Vec3 requested = Vec3::Zero();
  Vec3 used = Vec3::Zero();
  double moved = 0.0;  // [m]
  std::string why;     // "" when not moved
};

// Makes `p` a valid planning endpoint: inside the map bounds (on them is fine) and not inside a
// box; then moved into the free bounds (off the floor and walls by the vehicle's half-size
// plus the clearance), and, when it is still within the clearance of a box, to the nearest
// point within 0.5 m (2 cm grid) that keeps the clearance and that the vehicle reaches on a
// straight line without touching anything. Throws InputError (naming `what` and the map) when
// there is no such point.
Endpoint ResolveEndpoint(const Map& map, const CollisionWorld& world, const Vec3& p,
                         const std::string& what);

// Start and goal at once, sharing the clearance-free world both checks need. A point outside the
// bounds is reported at `*_where` (where it was given; default: the map file).
std::pair<Endpoint, Endpoint> ResolveEndpoints(const Map& map, const CollisionWorld& world,
                                               const Vec3& start, const Vec3& goal,
                                               const SourceLocation& start_where = {},
                                               const SourceLocation& goal_where = {});

// The largest acceleration the vehicle can follow [m/s^2]: horizontally what the tilt limit
// and the rotors' thrust allow, vertically what the thrust leaves above gravity.
double ReachableAcceleration(const FlightSetup& setup);

// A warning in words when the trajectory's limits ask more than the vehicle can give (""
// otherwise).
std::string LimitsWarning(const FlightSetup& setup);

// One line per moved endpoint: "start moved 0.125 m off the bounds/floor: a -> b" ("" when
// neither moved).
std::string DescribeMoves(const Endpoint& start, const Endpoint& goal);

struct PlanOutcome {
  Endpoint start;
  Endpoint goal;
  std::vector<Endpoint> via;  // a mission's goals before the last, in order
  PlanResult result;
  // the minimum-snap trajectory along the path, when there is a path
  std::optional<TrajectoryResult> trajectory;
  // when the lattice planned: its size and build time (query time is result.stats)
  std::optional<LatticeStats> lattice;
  std::string planner;            // the planner's name, as registered
  double fallback_spacing = 0.0;  // [m] of the lattice that took over from RRT* (0: none)
  // PlanStatus::kPathBlocked: what blocks the given path at result.stats.blocked_point, e.g.
  // "box 'wall' (within the 0.15 m kept from it)" or "the map's bounds"
  std::string blocked_by;
};

// A given path that is blocked, in words: "point 2 (0 is the start) at (1, 2, 0.5) m is not
// free: box 'wall' ..." or "the leg to point 2 leaves free space at (...) m: box 'wall' ...".
std::string DescribeBlockedPath(const PlanOutcome& plan);

// The planner a set-up uses: [planner] kind, where "auto" is the lattice for a city-sized map
// and RRT* otherwise.
std::string PlannerKindFor(const FlightSetup& setup);
// What the set-up's planner is made from (its kind, RRT*'s and the lattice's parameters, the
// given waypoints).
PlannerConfig PlannerConfigFor(const FlightSetup& setup);

// The lattice that takes over when RRT* finds no path: over the whole free space, as fine as
// 300,000 points allow (5 cm at the finest).
LatticeParams FallbackLattice(const Aabb& free_bounds);

// Plans the set-up's start to goal with its planning settings (its seed seeds the planner), then
// turns the path into a trajectory that keeps the trajectory clearance. A mission plans a leg
// from each goal to the next (each leg seeded from the seed) and flies one trajectory through
// all of them, or one per leg joined by holds when it stops at its goals. Throws InputError for
// unusable endpoints (or a missing goal); a missing path or trajectory is a status. Without
// `with_trajectory`, only the path.
PlanOutcome PlanFlight(const FlightSetup& setup, bool with_trajectory = true);

// The lattice PlanFlight builds for `setup` (altitudes counted from the map's floor).
LatticeParams LatticeParamsFor(const FlightSetup& setup);

// The trajectory generator's parameters for the set-up: min-time gets the vehicle's mass,
// inertia, allocation, rotor range and top speed; snap without caps gets its 2 m/s, 2 m/s^2.
TrajectoryParams TrajectoryParamsFor(const FlightSetup& setup);
// PlanFlight's second half: the trajectory along `path`, keeping the trajectory clearance. With
// a baseline method, min-snap's waypoints and segment times carry the baseline's polynomials.
TrajectoryResult TrajectoryAlong(const FlightSetup& setup, const std::vector<Vec3>& path);

// A map wider than 200 m (a city): planned on a lattice (with [planner] kind = auto) and flown
// in a scene that keeps only the buildings near the route.
bool IsCityScale(const Map& map);

// trajectory.csv: t,x,y,z,vx,vy,vz,ax,ay,az every 1/rate seconds from 0 to the end [s, m, m/s,
// m/s^2].
std::string TrajectoryCsv(const PiecewiseTrajectory& trajectory, double rate = 100.0);

}  // namespace aerobox
