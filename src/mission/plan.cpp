#include "mission/plan.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <tuple>

#include "common/drag.h"
#include "common/error.h"
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

// The wind beyond its mean [m/s] a trajectory keeps a reserve for: wind_reserve times the
// turbulence's largest intensity, plus the strongest gust's peak; none when wind_reserve is 0.
double WindExcess(const FlightSetup& setup) {
  const WindParams& wind = setup.wind;
  const double reserve = setup.planning.trajectory.wind_reserve;
  if (!(reserve > 0)) return 0.0;
  const double turbulence =
      wind.turbulence == Turbulence::kDryden ? reserve * wind.intensity.maxCoeff() : 0.0;
  double gust = 0.0;
  for (const Gust& g : wind.gusts) gust = std::max(gust, std::abs(g.peak));
  return turbulence + gust;
}

// Keeps back, from the tilt and the rotors' top thrust, the drag [m/s^2] that `excess` [m/s]
// more wind adds to the mean wind's on a vehicle at rest: the trajectory is slower, and the
// controller has the margin to meet the wind. (Moving, the vehicle meets more drag per m/s of
// wind; the trajectory's thrust margin is kept for that and for the controller.)
void ReserveForWind(double excess, TrajectoryParams* params) {
  FlatnessLimits& limits = params->vehicle;
  const double mean = limits.wind.norm();
  const double extra = DragAcceleration(limits.drag, Vec3(mean + excess, 0, 0)).norm() -
                       DragAcceleration(limits.drag, Vec3(mean, 0, 0)).norm();
  if (!(extra > 0)) return;
  params->max_tilt = std::max(0.05, params->max_tilt - std::atan(extra / kGravity));
  // the rotors keep at least 5 % above hover (never more than they have)
  const double hover = limits.mass * kGravity / kNumRotors;
  const double floor = std::min(limits.max_rotor_thrust, 1.05 * hover);
  limits.max_rotor_thrust =
      std::max(floor, limits.max_rotor_thrust - limits.mass * extra / kNumRotors);
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

PlannerConfig PlannerConfigFor(const FlightSetup& setup) {
  PlannerConfig config;
  config.kind = PlannerKindFor(setup);
  if (config.kind == "rrt_star") {
    config.params = PluginParameters::Of(setup.planning.rrt);
  } else if (config.kind == "lattice") {
    config.params = PluginParameters::Of(LatticeParamsFor(setup));
  } else if (config.kind == "waypoints") {
    config.params = PluginParameters::Of(WaypointsParams{setup.planning.waypoints});
  } else {
    config.params = setup.planning.planner_params;  // a registered planner's own
  }
  return config;
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

namespace {

// What makes p not free, in words.
std::string BlockedBy(const Map& map, const CollisionWorld& world, const Vec3& p) {
  const std::optional<size_t> box = world.BlockingBox(p);
  if (!box) return "the map's bounds (less the vehicle's half size and the clearance)";
  const std::string name = "box '" + map.boxes[*box].name + "'";
  if (world.OverlappingBox(p)) return name + " (the vehicle would overlap it)";
  return name + " (within the " + FormatNumber(world.params().clearance) +
         " m clearance kept from it)";
}

// One leg from `from` to `to` with the set-up's planner, seeded with `seed`, and the lattice
// when RRT* gives up; fills the outcome's result, planner and lattice.
void PlanLeg(const FlightSetup& setup, const CollisionWorld& world, const Vec3& from,
             const Vec3& to, std::uint64_t seed, PlanOutcome* outcome) {
  const PlanningSettings& settings = setup.planning;
  const PlannerContext context{
      world.free_bounds(),
      Validity{[&world](const Vec3& p) { return world.IsPointFree(p); },
               [&world](const Vec3& a, const Vec3& b) { return world.IsSegmentFree(a, b); }},
      seed};
  PlannerConfig config = PlannerConfigFor(setup);
  outcome->planner = config.kind;
  outcome->result = MakePlanner(config, context)->Plan(from, to);
  if (outcome->result.status == PlanStatus::kPathBlocked) {
    outcome->blocked_by = BlockedBy(setup.map, world, outcome->result.stats.blocked_point);
  }
  if (config.kind == "lattice") {
    outcome->lattice = LatticeStats{outcome->result.stats.nodes, outcome->result.stats.edges,
                                    outcome->result.stats.build_time};
  }
  // RRT* gave up on a map it could not search to the end in its budget (long narrow passages):
  // a fine lattice over the map is exhaustive at its spacing, so "no path" is said only when
  // neither finds one
  if (outcome->result.status == PlanStatus::kNoPathWithinBudget && config.kind == "rrt_star" &&
      settings.lattice_fallback) {
    const LatticeParams lattice = FallbackLattice(world.free_bounds());
    config = {"lattice", PluginParameters::Of(lattice)};
    PlanResult fallback = MakePlanner(config, context)->Plan(from, to);
    outcome->fallback_spacing = lattice.spacing;
    outcome->lattice =
        LatticeStats{fallback.stats.nodes, fallback.stats.edges, fallback.stats.build_time};
    fallback.stats.planning_time += outcome->result.stats.planning_time;
    fallback.stats.iterations = outcome->result.stats.iterations;
    fallback.stats.time_capped |= outcome->result.stats.time_capped;
    fallback.tree = std::move(outcome->result.tree);
    outcome->result = std::move(fallback);
    outcome->planner = "lattice (RRT* found no path)";
  }
}

// Adds a later leg's plan to the mission's: the path continues (the leg's first point is the
// last one's end), the counts and times add up, the first failure stays.
void AppendLeg(PlanOutcome&& leg, PlanOutcome* mission) {
  PlanResult& all = mission->result;
  const PlanResult& next = leg.result;
  if (all.status == PlanStatus::kSolved && next.status != PlanStatus::kSolved) {
    all.status = next.status;
    all.stats.blocked_leg = next.stats.blocked_leg;
    all.stats.blocked_point = next.stats.blocked_point;
    mission->blocked_by = leg.blocked_by;
  }
  if (next.status == PlanStatus::kSolved && !all.path.empty()) {
    all.path.insert(all.path.end(), next.path.begin() + 1, next.path.end());
  }
  PlanStats& a = all.stats;
  const PlanStats& b = next.stats;
  a.iterations += b.iterations;
  a.nodes += b.nodes;
  a.planning_time += b.planning_time;
  a.build_time += b.build_time;
  a.time_capped |= b.time_capped;
  if (a.final_cost >= 0 && b.final_cost >= 0) a.final_cost += b.final_cost;
  if (a.first_cost >= 0 && b.first_cost >= 0) a.first_cost += b.first_cost;
  all.tree.insert(all.tree.end(), next.tree.begin(), next.tree.end());
  if (leg.planner != mission->planner &&
      leg.planner.find("RRT* found no path") != std::string::npos) {
    mission->planner = leg.planner;
    mission->fallback_spacing = leg.fallback_spacing;
  }
  if (leg.lattice && !mission->lattice) mission->lattice = leg.lattice;
}

// A constant segment: the vehicle holds `p` for `duration` seconds.
PolynomialSegment Hold(const Vec3& p, double duration) {
  Eigen::MatrixXd coefficients = Eigen::MatrixXd::Zero(3, 8);
  coefficients.col(0) = p;
  return PolynomialSegment(coefficients, duration);
}

// A mission that stops at its goals: one rest-to-rest trajectory per leg, joined by holds.
TrajectoryResult StoppingTrajectory(const FlightSetup& setup, const std::vector<Vec3>& path,
                                    const std::vector<Vec3>& goals) {
  TrajectoryResult joined;
  joined.status = TrajectoryStatus::kSolved;
  std::vector<PolynomialSegment> segments;
  size_t from = 0;
  for (size_t g = 0; g < goals.size(); ++g) {
    size_t to = from + 1;
    while (to + 1 < path.size() && (path[to] - goals[g]).norm() > 1e-9) ++to;
    const std::vector<Vec3> leg(path.begin() + static_cast<long>(from),
                                path.begin() + static_cast<long>(to) + 1);
    TrajectoryResult part = TrajectoryAlong(setup, leg);
    joined.stats.solve_time += part.stats.solve_time;
    joined.stats.refinements += part.stats.refinements;
    joined.stats.solver_message = part.stats.solver_message;
    if (part.status != TrajectoryStatus::kSolved) {
      joined.status = part.status;
      joined.stats.solver_message = part.stats.solver_message;
      return joined;
    }
    if (joined.stats.binding_limit.ratio < part.stats.binding_limit.ratio) {
      joined.stats.binding_limit = part.stats.binding_limit;
      joined.stats.binding_limit.t += joined.trajectory.duration();
    }
    for (const PolynomialSegment& s : part.trajectory.segments()) segments.push_back(s);
    joined.waypoints.insert(joined.waypoints.end(), part.waypoints.begin() + (g == 0 ? 0 : 1),
                            part.waypoints.end());
    joined.corridors.insert(joined.corridors.end(), part.corridors.begin(), part.corridors.end());
    if (g + 1 < goals.size() && setup.hold > 0) {
      segments.push_back(Hold(goals[g], setup.hold));
      joined.corridors.push_back(std::nullopt);
    }
    joined.trajectory = PiecewiseTrajectory(segments);
    from = to;
  }
  joined.stats.segments = static_cast<int>(segments.size());
  joined.stats.duration = joined.trajectory.duration();
  joined.stats.max_speed = joined.trajectory.MaxNorm(kVelocity, 0.01);
  joined.stats.max_accel = joined.trajectory.MaxNorm(kAcceleration, 0.01);
  return joined;
}

}  // namespace

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
  for (size_t i = 0; i < setup.via.size(); ++i) {
    outcome.via.push_back(
        ResolveEndpoint(setup.map, world, setup.via[i], "goals[" + std::to_string(i) + "]"));
  }
  // the legs: start, the goals in order, the last goal
  std::vector<Vec3> stops = {outcome.start.used};
  for (const Endpoint& e : outcome.via) stops.push_back(e.used);
  stops.push_back(outcome.goal.used);
  for (size_t i = 1; i < stops.size(); ++i) {
    if ((stops[i] - stops[i - 1]).norm() < 1e-3) {
      throw InputError(setup.goal_where, i + 1 == stops.size() ? "goal" : "goals",
                       "goal " + std::to_string(i) + " at " + FormatVector(stops[i], ", ") +
                           " is where the flight already is (once inside the free space): "
                           "there is nothing to fly; give another goal");
    }
  }
  PlanLeg(setup, world, stops[0], stops[1], setup.seed, &outcome);
  for (size_t i = 2; i < stops.size(); ++i) {
    // each leg its own planner seed, derived from the set-up's
    PlanOutcome leg;
    PlanLeg(setup, world, stops[i - 1], stops[i], setup.seed + 1000003ULL * (i - 1), &leg);
    AppendLeg(std::move(leg), &outcome);
  }
  if (outcome.result.status != PlanStatus::kSolved || !with_trajectory) return outcome;
  if (setup.stop_at_goals && !outcome.via.empty()) {
    std::vector<Vec3> goals(stops.begin() + 1, stops.end());
    outcome.trajectory = StoppingTrajectory(setup, outcome.result.path, goals);
  } else {
    outcome.trajectory = TrajectoryAlong(setup, outcome.result.path);
  }
  return outcome;
}

std::string DescribeBlockedPath(const PlanOutcome& plan) {
  const PlanStats& stats = plan.result.stats;
  const std::string at = "(" + FormatVector(stats.blocked_point, ", ") + ") m";
  const std::string where = stats.blocked_leg == 0
                                ? "the start " + at + " is not free"
                                : "the leg to point " + std::to_string(stats.blocked_leg) +
                                      " (0 is the start) leaves free space at " + at;
  return where + ": " + plan.blocked_by;
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
    ReserveForWind(WindExcess(setup), &params);  // before the braking below uses the tilt
  }
  if (setup.HasUnknown()) {
    // boxes may appear: no faster than the vehicle can stop within what its sensor sees
    const double margin =
        0.5 * setup.vehicle.collision_size.maxCoeff() + setup.planning.trajectory_clearance;
    params.max_speed =
        std::min(params.max_speed, SensingSpeedLimit(setup.sensing, setup.replan,
                                                     BrakingDeceleration(params.max_tilt), margin));
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
  config.params.ipopt.injected_failure = setup.faults.ipopt_failure;  // fault tests only
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
