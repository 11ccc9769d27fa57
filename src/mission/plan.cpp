#include "mission/plan.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <tuple>

#include "common/error.h"
#include "common/fault_injection.h"
#include "common/number_format.h"
#include "planning/path_simplify.h"
#include "planning/planner.h"
#include "telemetry/csv_table.h"

namespace aerobox {
namespace {

// Offsets of a 2 cm grid within 0.5 m, nearest first: the search order for a usable endpoint.
const std::vector<Vec3>& SearchOffsets() {
  static const std::vector<Vec3> offsets = [] {
    constexpr double kStep = 0.02;
    constexpr int kCells = 25;  // 0.5 m / 2 cm
    std::vector<Vec3> all;
    for (int i = -kCells; i <= kCells; ++i) {
      for (int j = -kCells; j <= kCells; ++j) {
        for (int k = -kCells; k <= kCells; ++k) {
          const Vec3 offset = kStep * Vec3(i, j, k);
          if (offset.norm() <= kCells * kStep + 1e-9) all.push_back(offset);
        }
      }
    }
    std::stable_sort(all.begin(), all.end(),
                     [](const Vec3& a, const Vec3& b) { return a.norm() < b.norm(); });
    return all;
  }();
  return offsets;
}

// The same world without the clearance: where the vehicle itself fits.
CollisionWorld Touching(const Map& map, const CollisionWorld& world) {
  CollisionParams tight = world.params();
  tight.clearance = 0.0;
  return CollisionWorld(map, tight);
}

Endpoint Resolve(const Map& map, const CollisionWorld& world, const CollisionWorld& touching,
                 const Vec3& p, const std::string& what, SourceLocation where) {
  if (where.file.empty()) where = {map.source, 0};
  if (!map.bounds.Contains(p)) {
    throw InputError(where, what, FormatVector(p, ", ") + " lies outside the map bounds");
  }
  // the vehicle itself (no clearance) must fit where it is asked to be, once off the walls
  const Vec3 physical = touching.ProjectIntoFreeBounds(p).point;
  if (const auto box = touching.OverlappingBox(physical)) {
    const Box& b = map.boxes[*box];
    throw InputError(
        {map.source, b.line}, what,
        FormatVector(p, ", ") + " lies inside " + b.name + " (the vehicle does not fit)");
  }

  Endpoint endpoint;
  endpoint.requested = p;
  const Projection inside = world.ProjectIntoFreeBounds(p);
  endpoint.used = inside.point;
  if (inside.moved > 0) endpoint.why = "off the bounds/floor";
  if (!world.IsPointFree(endpoint.used)) {
    bool found = false;
    for (const Vec3& offset : SearchOffsets()) {
      const Vec3 candidate = inside.point + offset;
      if (world.IsPointFree(candidate) && touching.IsSegmentFree(physical, candidate)) {
        endpoint.used = candidate;
        endpoint.why = "out of the clearance of obstacles";
        found = true;
        break;
      }
    }
    if (!found) {
      throw InputError(where, what,
                       FormatVector(p, ", ") + " is within the " +
                           FormatNumber(world.params().clearance) +
                           " m clearance of an obstacle and no point within 0.5 m keeps it and "
                           "is reachable in a straight line; move it or lower the clearance");
    }
  }
  endpoint.moved = (endpoint.used - p).norm();
  return endpoint;
}

}  // namespace

Endpoint ResolveEndpoint(const Map& map, const CollisionWorld& world, const Vec3& p,
                         const std::string& what) {
  return Resolve(map, world, Touching(map, world), p, what, {});
}

std::pair<Endpoint, Endpoint> ResolveEndpoints(const Map& map, const CollisionWorld& world,
                                               const Vec3& start, const Vec3& goal,
                                               const SourceLocation& start_where,
                                               const SourceLocation& goal_where) {
  const CollisionWorld touching = Touching(map, world);
  return {Resolve(map, world, touching, start, "start", start_where),
          Resolve(map, world, touching, goal, "goal", goal_where)};
}

namespace {

// The tilt limit of the set-up's controller [rad].
double ControllerTilt(const FlightSetup& setup) {
  return setup.controller.kind == "se3" ? setup.controller.se3.max_tilt
                                        : setup.controller.cascade.max_tilt;
}

}  // namespace

double ReachableAcceleration(const FlightSetup& setup) {
  const QuadParams& v = setup.vehicle;
  const double thrust = kNumRotors * v.MaxRotorThrust() / v.mass;  // [m/s^2] straight up
  const double tilt = ControllerTilt(setup);
  const double horizontal = std::min(
      kGravity * std::tan(tilt), std::sqrt(std::max(0.0, thrust * thrust - kGravity * kGravity)));
  return std::min(horizontal, thrust - kGravity);
}

std::string LimitsWarning(const FlightSetup& setup) {
  const double reachable = ReachableAcceleration(setup);
  const double asked = TrajectoryParamsFor(setup).max_accel;
  if (setup.planning.trajectory.objective == TimeObjective::kMinTime) {
    // the vehicle's limits decide; a cap above them only does nothing
    const double tilt = ControllerTilt(setup);
    if (setup.planning.trajectory.max_tilt < tilt) return "";
    return "the trajectory may tilt " + FormatNumber(setup.planning.trajectory.max_tilt) +
           " rad, the controller only " + FormatNumber(tilt) +
           " rad: expect it to lag behind ([trajectory] max_tilt)";
  }
  if (asked <= reachable) return "";
  return "the trajectory may accelerate at " + FormatNumber(asked) + " m/s^2, but this vehicle " +
         "reaches about " + FormatNumber(std::floor(reachable * 10) / 10) +
         " m/s^2 (its tilt limit and thrust); expect it to lag behind (--max-accel " +
         FormatNumber(std::floor(reachable * 10) / 10) + " is reachable)";
}

std::string DescribeMoves(const Endpoint& start, const Endpoint& goal) {
  std::string text;
  for (const Endpoint* e : {&start, &goal}) {
    if (!(e->moved > 0)) continue;
    char moved[32];
    std::snprintf(moved, sizeof(moved), "%.3f", e->moved);
    // to the millimetre: 0.65, not -0.6499999999999999
    const auto point = [](const Vec3& p) {
      return FormatVector((p * 1000).array().round() / 1000, ", ");
    };
    text += std::string(e == &start ? "start" : "goal") + " moved " + moved + " m " + e->why +
            ": " + point(e->requested) + " -> " + point(e->used) + "\n";
  }
  return text;
}

bool IsCityScale(const Map& map) { return map.bounds.Size().head<2>().maxCoeff() > 200.0; }

std::string PlannerKindFor(const FlightSetup& setup) {
  if (setup.planning.planner != "auto") return setup.planning.planner;
  return IsCityScale(setup.map) ? "lattice" : "rrt_star";
}

LatticeParams FallbackLattice(const Aabb& free_bounds) {
  // as fine as kMaxFallbackNodes points allow, and no finer than 5 cm
  constexpr double kMaxFallbackNodes = 3e5;
  constexpr double kFinest = 0.05;  // [m]
  const Vec3 size = free_bounds.Size().cwiseMax(kFinest);
  LatticeParams params;
  params.spacing = std::max(kFinest, std::cbrt(size.prod() / kMaxFallbackNodes));
  params.vertical_spacing = params.spacing;
  params.min_altitude = free_bounds.min.z();
  params.max_altitude = free_bounds.max.z();
  return params;
}

PlanOutcome PlanFlight(const FlightSetup& setup, bool with_trajectory) {
  const PlanningSettings& settings = setup.planning;
  if (settings.trajectory_method == "given") {
    // a trajectory from elsewhere: nothing to plan; it starts and ends where it does
    PlanOutcome outcome;
    outcome.planner = "none (a given trajectory)";
    for (const TrajectorySample& s : settings.given_trajectory)
      outcome.result.path.push_back(s.p_W);
    outcome.result.status = PlanStatus::kSolved;
    outcome.start.requested = outcome.start.used = outcome.result.path.front();
    outcome.goal.requested = outcome.goal.used = outcome.result.path.back();
    outcome.result.stats.final_cost = PathLength(outcome.result.path);
    outcome.trajectory = TrajectoryAlong(setup, outcome.result.path);
    return outcome;
  }
  if (!setup.goal) throw InputError({setup.map.source, 0}, "goal", "no goal given");
  if (setup.start_origin == kNoStart) {
    throw InputError(setup.start_where, "start",
                     "no start given and no free spot found on the floor or on a block; give "
                     "one with --start or in the scenario");
  }
  const CollisionWorld world(setup.map, setup.PlannerCollision());
  PlanOutcome outcome;
  std::tie(outcome.start, outcome.goal) = ResolveEndpoints(
      setup.map, world, setup.start, *setup.goal, setup.start_where, setup.goal_where);
  if ((outcome.start.used - outcome.goal.used).norm() < 1e-3) {
    throw InputError(setup.goal_where, "goal",
                     "the goal " + FormatVector(*setup.goal, ", ") +
                         " is where the flight starts (" + FormatVector(outcome.start.used, ", ") +
                         " once both are inside the free space): there is nothing to fly; "
                         "give another goal");
  }
  const PlannerContext context{
      world.free_bounds(),
      Validity{[&world](const Vec3& p) { return world.IsPointFree(p); },
               [&world](const Vec3& a, const Vec3& b) { return world.IsSegmentFree(a, b); }},
      setup.seed};
  PlannerConfig config;
  config.kind = PlannerKindFor(setup);
  config.rrt = settings.rrt;
  config.lattice = LatticeParamsFor(setup);
  config.waypoints = settings.waypoints;
  outcome.planner = config.kind;
  outcome.result = MakePlanner(config, context)->Plan(outcome.start.used, outcome.goal.used);
  if (config.kind == "lattice") {
    outcome.lattice = LatticeStats{outcome.result.stats.nodes, outcome.result.stats.edges,
                                   outcome.result.stats.build_time};
  }
  // RRT* gave up on a map it could not search to the end in its budget (long narrow passages):
  // a fine lattice over the map is exhaustive at its spacing, so "no path" is said only when
  // neither finds one
  if (outcome.result.status == PlanStatus::kNoPathWithinBudget && config.kind == "rrt_star" &&
      settings.lattice_fallback) {
    config.kind = "lattice";
    config.lattice = FallbackLattice(world.free_bounds());
    PlanResult fallback = MakePlanner(config, context)->Plan(outcome.start.used, outcome.goal.used);
    outcome.fallback_spacing = config.lattice.spacing;
    outcome.lattice =
        LatticeStats{fallback.stats.nodes, fallback.stats.edges, fallback.stats.build_time};
    fallback.stats.planning_time += outcome.result.stats.planning_time;
    fallback.stats.iterations = outcome.result.stats.iterations;
    fallback.tree = std::move(outcome.result.tree);
    outcome.result = std::move(fallback);
    outcome.planner = "lattice (RRT* found no path)";
  }
  if (outcome.result.status != PlanStatus::kSolved || !with_trajectory) return outcome;
  outcome.trajectory = TrajectoryAlong(setup, outcome.result.path);
  return outcome;
}

LatticeParams LatticeParamsFor(const FlightSetup& setup) {
  LatticeParams params = setup.planning.lattice;
  params.min_altitude += setup.map.bounds.min.z();
  params.max_altitude += setup.map.bounds.min.z();
  params.seed = setup.seed;
  return params;
}

TrajectoryParams TrajectoryParamsFor(const FlightSetup& setup) {
  TrajectoryParams params = setup.planning.trajectory;
  if (params.objective == TimeObjective::kSnap) {
    // the snap objective scales to its limits: without caps, its own defaults
    const TrajectoryParams snap;
    if (!std::isfinite(params.max_speed)) params.max_speed = snap.max_speed;
    if (!std::isfinite(params.max_accel)) params.max_accel = snap.max_accel;
    return params;
  }
  const QuadParams& v = setup.vehicle;
  FlatnessLimits& limits = params.vehicle;
  limits.mass = v.mass;
  limits.inertia = v.inertia;
  limits.allocation = AllocationMatrix(v);
  limits.min_rotor_thrust = v.MinRotorThrust();
  limits.max_rotor_thrust = v.MaxRotorThrust();
  limits.max_speed = v.max_speed;
  limits.yaw = 0.0;  // the flight holds the start's yaw, level at rest (FlyTrajectory)
  if (setup.aero.Enabled()) {
    // the thrust also pays for the drag of the parts that are on, in the mean wind
    const DragModel drag = LumpedDrag(v);
    if (setup.aero.rotor_drag) limits.drag.linear = drag.linear;
    if (setup.aero.body_drag) limits.drag.quadratic = drag.quadratic;
    limits.wind = setup.wind.mean;
  }
  return params;
}

TrajectoryResult TrajectoryAlong(const FlightSetup& setup, const std::vector<Vec3>& path) {
  const PlanningSettings& settings = setup.planning;
  const CollisionWorld trajectory_world(setup.map, setup.TrajectoryCollision());
  const TrajectoryWorld view{
      [&trajectory_world](const Aabb& box) { return trajectory_world.IsBoxFree(box); },
      [&trajectory_world](const Vec3& a, const Vec3& b) {
        return trajectory_world.IsSegmentFree(a, b);
      }};
  GeneratorConfig config;
  config.method = settings.trajectory_method;
  config.params = TrajectoryParamsFor(setup);
  config.params.ipopt.injected_failure = InjectedFault("ipopt").has_value();  // fault tests only
  config.given = settings.given_trajectory;
  return MakeGenerator(config)->Generate(path, view);
}

std::string TrajectoryCsv(const PiecewiseTrajectory& trajectory, double rate) {
  CsvTable table({"t", "x", "y", "z", "vx", "vy", "vz", "ax", "ay", "az"});
  const double duration = trajectory.duration();
  const long samples = static_cast<long>(std::floor(duration * rate + 1e-9));
  Eigen::Matrix<double, 10, 1> row;
  for (long i = 0; i <= samples; ++i) {
    const double t = static_cast<double>(i) / rate;
    row << t, trajectory.Evaluate(t, kPosition), trajectory.Evaluate(t, kVelocity),
        trajectory.Evaluate(t, kAcceleration);
    table.AddRow(row);
  }
  return table.Text();
}

}  // namespace aerobox
