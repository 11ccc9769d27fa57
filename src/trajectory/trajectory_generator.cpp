#include "trajectory/trajectory_generator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "common/number_format.h"
#include "trajectory/time_allocation.h"

namespace aerobox {
namespace {

// Rounds of stretching the segments a corridor-constrained solve left over the limits.
constexpr int kMaxRepairs = 3;

// How often a segment whose bounding box is not free is halved before it goes without a corridor.
constexpr int kMaxSplits = 4;

// Waypoints this close [m] make segments of a few milliseconds, on which Ipopt fails
// (restoration failed, maximum iterations) where the path itself is fine.
constexpr double kMergeDistance = 0.02;

// The path without repeated points, and without an interior waypoint within kMergeDistance of
// the one before it when the leg that skips it is free (the ends never move).
std::vector<Vec3> WithoutNearRepeats(const std::vector<Vec3>& path, const TrajectoryWorld& world) {
  std::vector<Vec3> points;
  for (const Vec3& p : path) {
    if (points.empty() || (p - points.back()).norm() > 1e-6) points.push_back(p);
  }
  std::vector<Vec3> merged;
  for (size_t i = 0; i < points.size(); ++i) {
    const bool interior = i > 0 && i + 1 < points.size();
    if (interior && (points[i] - merged.back()).norm() < kMergeDistance &&
        world.segment_free(merged.back(), points[i + 1])) {
      continue;
    }
    if (!interior && i > 0 && merged.size() > 1 &&
        (points[i] - merged.back()).norm() < kMergeDistance &&
        world.segment_free(merged[merged.size() - 2], points[i])) {
      merged.back() = points[i];  // the goal stays; the waypoint just before it goes
      continue;
    }
    merged.push_back(points[i]);
  }
  return merged;
}

// Halves segments whose bounding box is not free (a diagonal past a corner), so that each
// piece can have a corridor; gives up on a segment after kMaxSplits halvings.
std::vector<Vec3> SplitForCorridors(const std::vector<Vec3>& waypoints, const BoxFree& box_free) {
  std::vector<Vec3> out = {waypoints.front()};
  for (size_t i = 1; i < waypoints.size(); ++i) {
    // depth-first halving of [a, b]
    std::vector<std::pair<Vec3, int>> pending = {{waypoints[i], 0}};
    Vec3 a = waypoints[i - 1];
    while (!pending.empty()) {
      const auto [b, depth] = pending.back();
      if (depth < kMaxSplits && !box_free({a.cwiseMin(b), a.cwiseMax(b)})) {
        pending.push_back({0.5 * (a + b), depth + 1});
        pending[pending.size() - 2].second = depth + 1;
        continue;
      }
      pending.pop_back();
      out.push_back(b);
      a = b;
    }
  }
  return out;
}

// Cuts straight segments longer than `piece` [m] into equal pieces: a minimum-snap segment
// peaks in its middle, a chain of short ones can hold a cruise.
std::vector<Vec3> CutLongSegments(const std::vector<Vec3>& waypoints, double piece) {
  std::vector<Vec3> out = {waypoints.front()};
  for (size_t i = 1; i < waypoints.size(); ++i) {
    const Vec3& a = waypoints[i - 1];
    const Vec3& b = waypoints[i];
    const int pieces = std::max(1, static_cast<int>(std::ceil((b - a).norm() / piece - 1e-9)));
    for (int k = 1; k < pieces; ++k) out.push_back(a + (b - a) * (static_cast<double>(k) / pieces));
    out.push_back(b);
  }
  return out;
}

// The utilisation each segment's time is scaled towards: a little under the limits, so that the
// final check (on the corridor-constrained solve) rarely has to stretch anything.
constexpr double kMinTimeTarget = 0.95;
constexpr double kTimeRange = 4.0;

// Each segment's time times the square root of the factor that would put its worst point at
// the target (half the way, in the logarithm: neighbouring segments share their waypoints'
// derivatives, so a full step overshoots). Returns the largest relative change.
double ScaleSegmentTimes(const std::vector<FeasibilityCheck>& checks,
                         std::vector<double>* durations) {
  double change = 0.0;
  for (size_t i = 0; i < durations->size() && i < checks.size(); ++i) {
    const double need = checks[i].scale / kMinTimeTarget;
    if (!(need > 0) || !std::isfinite(need)) continue;
    const double factor = std::clamp(std::sqrt(need), 0.5, 2.0);
    (*durations)[i] *= factor;
    change = std::max(change, std::abs(factor - 1.0));
  }
  return change;
}

// The worst segment's scale: > 1 when the trajectory asks too much somewhere.
double WorstScale(const std::vector<FeasibilityCheck>& checks) {
  double worst = 0.0;
  for (const FeasibilityCheck& check : checks) worst = std::max(worst, check.scale);
  return worst;
}

// Minimum-time segment times on the unconstrained (closed-form) minimum-snap trajectory: from
// `initial`, each segment's time is rescaled by its own worst point (CheckSegments), for
// params.time_iterations rounds or until none changes by more than 1 %. Returns the times of
// the round that was fastest once stretched uniformly to be feasible, and that duration.
std::pair<std::vector<double>, double> MinTimeFrom(const std::vector<Vec3>& waypoints,
                                                   std::vector<double> durations,
                                                   const FlatnessLimits& limits,
                                                   const TrajectoryParams& params) {
  // each segment stays within a factor kTimeRange of its start: a segment that cannot be made
  // feasible on its own (its neighbours decide) must not run away
  const std::vector<double> initial = durations;
  std::vector<double> best = durations;
  double best_total = std::numeric_limits<double>::infinity();
  MinSnapProblem problem;
  problem.waypoints = waypoints;
  for (int k = 0; k < params.time_iterations; ++k) {
    problem.durations = durations;
    const PiecewiseTrajectory trajectory = SolveMinSnapClosedForm(problem);
    const std::vector<FeasibilityCheck> checks =
        CheckSegments(trajectory, limits, params.check_step);
    // uniform stretching by s scales every limit's ratio to its own order by 1/s, so the
    // feasible version of this round lasts duration * max(1, worst scale)
    const double stretch = std::max(1.0, WorstScale(checks));
    if (trajectory.duration() * stretch < best_total) {
      best_total = trajectory.duration() * stretch;
      best = durations;
      for (double& t : best) t *= stretch;
    }
    const double change = ScaleSegmentTimes(checks, &durations);
    for (size_t i = 0; i < durations.size(); ++i) {
      durations[i] = std::clamp(durations[i], initial[i] / kTimeRange, initial[i] * kTimeRange);
    }
    if (change < 0.01) break;
  }
  return {best, best_total};
}

// The time the closed-form trajectory on `durations` lasts once stretched uniformly to be
// feasible [s].
double FeasibleDuration(MinSnapProblem* problem, const std::vector<double>& durations,
                        const FlatnessLimits& limits, double dt) {
  problem->durations = durations;
  const PiecewiseTrajectory trajectory = SolveMinSnapClosedForm(*problem);
  return trajectory.duration() * std::max(1.0, CheckFeasibility(trajectory, limits, dt).scale);
}

// Pattern search on the feasible duration itself: each segment's time shrunk or stretched by
// `step`, kept when the whole trajectory, made feasible, gets shorter; the step halves when a
// sweep finds nothing. It finds what the per-segment scaling cannot: a segment slowed so that
// its neighbours may go faster. At most kSearchEvaluations solves.
std::vector<double> SearchDurations(const std::vector<Vec3>& waypoints, std::vector<double> best,
                                    const FlatnessLimits& limits, double dt) {
  constexpr int kSearchEvaluations = 400;
  MinSnapProblem problem;
  problem.waypoints = waypoints;
  double best_total = FeasibleDuration(&problem, best, limits, dt);
  int evaluations = 1;
  for (double step = 0.15; step > 0.01 && evaluations < kSearchEvaluations; step *= 0.5) {
    bool improved = true;
    while (improved && evaluations < kSearchEvaluations) {
      improved = false;
      for (size_t i = 0; i < best.size() && evaluations < kSearchEvaluations; ++i) {
        for (const double factor : {1.0 - step, 1.0 / (1.0 - step)}) {
          std::vector<double> trial = best;
          trial[i] *= factor;
          const double total = FeasibleDuration(&problem, trial, limits, dt);
          ++evaluations;
          if (total < best_total * (1.0 - 1e-4)) {
            best_total = total;
            best = std::move(trial);
            improved = true;
            break;
          }
        }
      }
    }
  }
  // feasible as it stands: stretched by what the last check asked
  problem.durations = best;
  const double stretch =
      std::max(1.0, CheckFeasibility(SolveMinSnapClosedForm(problem), limits, dt).scale);
  for (double& t : best) t *= stretch;
  return best;
}

// MinTimeFrom two starts, the faster kept: trapezoids that stop at every waypoint (they suit
// paths that turn at every waypoint), and trapezoids along each straight leg (long legs cut into
// pieces cruise through them).
std::vector<double> MinTimeDurations(const std::vector<Vec3>& waypoints,
                                     const FlatnessLimits& limits, const TrajectoryParams& params) {
  const double accel = std::min(kGravity * std::tan(limits.max_tilt), limits.max_accel);
  const auto stops = MinTimeFrom(waypoints, TrapezoidDurations(waypoints, limits.max_speed, accel),
                                 limits, params);
  const auto legs = MinTimeFrom(
      waypoints, TrapezoidDurationsAlongLegs(waypoints, limits.max_speed, accel), limits, params);
  const std::vector<double>& best = stops.second <= legs.second ? stops.first : legs.first;
  // the search costs a solve per trial: for the maps of a room, not for a city's hundreds of
  // segments
  constexpr size_t kSearchSegments = 60;
  if (best.size() > kSearchSegments) return best;
  return SearchDurations(waypoints, best, limits, params.check_step);
}

}  // namespace

const char* ToString(TimeObjective objective) {
  return objective == TimeObjective::kMinTime ? "min-time" : "snap";
}

FlatnessLimits EffectiveLimits(const TrajectoryParams& params) {
  FlatnessLimits limits = params.vehicle;
  const double hover = limits.mass * kGravity / 4.0;
  limits.max_rotor_thrust -= params.thrust_margin * (limits.max_rotor_thrust - hover);
  limits.min_rotor_thrust += params.thrust_margin * (hover - limits.min_rotor_thrust);
  limits.max_tilt = params.max_tilt;
  limits.max_rate = params.max_rate;
  limits.max_speed = std::min(params.vehicle.max_speed, params.max_speed);
  limits.max_vertical_speed = std::min(params.vehicle.max_speed, params.max_vertical_speed);
  limits.max_accel = params.max_accel;
  return limits;
}

void TrajectoryParams::Describe(Archive& a) {
  a.Enum({"objective", "", "the fastest the vehicle can fly, or min-snap scaled to the caps"},
         &objective, {{TimeObjective::kMinTime, "min-time"}, {TimeObjective::kSnap, "snap"}});
  a.Number({"max_speed", "m/s", "a speed cap (none: the vehicle's top speed decides)"}, &max_speed,
           0.01, 8.0);
  a.Number({"max_accel", "m/s^2", "an acceleration cap (none: the vehicle's thrust decides)"},
           &max_accel, 0.01, 10.0);
  a.Number({"thrust_margin", "", "min-time: share of each rotor's swing kept for the controller"},
           &thrust_margin, 0.0, 0.9);
  a.Number({"max_tilt", "rad", "min-time: the steepest tilt the trajectory asks"}, &max_tilt, 0.05,
           1.2);
  a.Number({"max_rate", "rad/s", "min-time: the fastest body rate the trajectory asks"}, &max_rate,
           0.1, 50.0);
  a.Number({"max_vertical_speed", "m/s", "min-time: the fastest climb or descent"},
           &max_vertical_speed, 0.01, 8.0);
  a.Number({"wind_reserve", "",
            "min-time, in wind with drag: tilt and thrust kept for this many turbulence "
            "intensities beyond the mean wind, plus the strongest gust (0: none)"},
           &wind_reserve, 0.0, 10.0);
  a.Boolean({"corridors", "", "keep the trajectory in boxes around the path (Ipopt)"},
            &use_corridors);
  a.Number({"corridor_growth", "m", "how far a corridor may reach past its segment's box"},
           &corridor_growth, 0.0, 100.0);
  a.Integer({"samples_per_segment", "", "constrained samples per segment"}, &samples_per_segment, 1,
            1000);
  a.Integer({"max_refinements", "", "rounds of inserting midpoints where it collides"},
            &max_refinements, 0, 100);
  a.Boolean({"closed_form_fallback", "", "when Ipopt fails, the closed form, refined and checked"},
            &closed_form_fallback);
}

void TrajectoryParams::Validate() const {
  const auto fail = [](const char* field, double value) {
    throw std::invalid_argument(std::string("TrajectoryParams.") + field +
                                " out of range: " + FormatNumber(value));
  };
  // a cap may be infinite (none): min-time does without; snap needs both (GenerateTrajectory)
  const bool min_time = objective == TimeObjective::kMinTime;
  if (!(max_speed > 0)) fail("max_speed", max_speed);
  if (!(max_accel > 0)) fail("max_accel", max_accel);
  if (min_time) {
    if (!(thrust_margin >= 0 && thrust_margin < 1)) fail("thrust_margin", thrust_margin);
    if (!(max_tilt > 0 && max_tilt < 1.5)) fail("max_tilt", max_tilt);
    if (!(max_rate > 0 && std::isfinite(max_rate))) fail("max_rate", max_rate);
    if (!(max_vertical_speed > 0 && std::isfinite(max_vertical_speed)))
      fail("max_vertical_speed", max_vertical_speed);
    if (time_iterations < 1) fail("time_iterations", time_iterations);
    if (!(cruise_piece > 0 && std::isfinite(cruise_piece))) fail("cruise_piece", cruise_piece);
  }
  if (!(corridor_growth >= 0 && std::isfinite(corridor_growth)))
    fail("corridor_growth", corridor_growth);
  if (!(corridor_margin >= 0 && std::isfinite(corridor_margin)))
    fail("corridor_margin", corridor_margin);
  if (samples_per_segment < 1) fail("samples_per_segment", samples_per_segment);
  if (max_refinements < 0) fail("max_refinements", max_refinements);
  if (time_refinement_steps < 0) fail("time_refinement_steps", time_refinement_steps);
  if (!(check_step > 0 && check_step <= 0.1)) fail("check_step", check_step);
}

const char* ToString(TrajectoryStatus status) {
  switch (status) {
    case TrajectoryStatus::kSolved:
      return "solved";
    case TrajectoryStatus::kInfeasible:
      return "infeasible";
    case TrajectoryStatus::kFailed:
      return "failed";
    case TrajectoryStatus::kCollides:
      return "collides after refinement";
  }
  return "?";
}

void MeasureTrajectory(const TrajectoryParams& params, TrajectoryResult* result) {
  if (result->trajectory.empty()) return;
  result->stats.duration = result->trajectory.duration();
  result->stats.max_speed = result->trajectory.MaxNorm(kVelocity, params.check_step);
  result->stats.max_accel = result->trajectory.MaxNorm(kAcceleration, params.check_step);
  result->stats.snap_cost = result->trajectory.SnapCost();
}

std::optional<double> FirstCollisionTime(const PiecewiseTrajectory& trajectory,
                                         const TrajectoryWorld& world, double step) {
  const double duration = trajectory.duration();
  const int steps = std::max(1, static_cast<int>(std::ceil(duration / step)));
  // consecutive samples are joined by straight segments, checked exactly; between samples the
  // curve leaves its chord by at most a_max step^2 / 8 (25 um at 2 m/s^2 and 10 ms)
  Vec3 previous = trajectory.Evaluate(0.0, kPosition);
  for (int i = 1; i <= steps; ++i) {
    const double t = duration * i / steps;
    const Vec3 p = trajectory.Evaluate(t, kPosition);
    if (!world.segment_free(previous, p)) return t;
    previous = p;
  }
  return std::nullopt;
}

namespace {

// One round of collision-aware refinement: true (with the status set) when result->trajectory
// stays free or the rounds are spent; otherwise the segment that first leaves free space gets
// its midpoint and false.
bool Refine(const TrajectoryWorld& world, const TrajectoryParams& params, int round,
            std::vector<Vec3>* waypoints, TrajectoryResult* result) {
  const std::optional<double> hit =
      FirstCollisionTime(result->trajectory, world, params.check_step);
  if (!hit) {
    result->status = TrajectoryStatus::kSolved;
    return true;
  }
  if (round >= params.max_refinements) {
    result->status = TrajectoryStatus::kCollides;
    return true;
  }
  const std::vector<double> knots = result->trajectory.KnotTimes();
  size_t segment = 0;
  while (segment + 2 < knots.size() && knots[segment + 1] < *hit) ++segment;
  std::vector<Vec3>& w = *waypoints;
  w.insert(w.begin() + static_cast<long>(segment) + 1, 0.5 * (w[segment] + w[segment + 1]));
  ++result->stats.refinements;
  return false;
}

}  // namespace

TrajectoryResult GenerateTrajectory(const std::vector<Vec3>& path, const TrajectoryWorld& world,
                                    const TrajectoryParams& params) {
  params.Validate();
  const auto begin = std::chrono::steady_clock::now();
  TrajectoryResult result;
  result.waypoints = WithoutNearRepeats(path, world);
  if (result.waypoints.size() < 2)
    throw std::invalid_argument("GenerateTrajectory: path too short");

  const bool min_time = params.objective == TimeObjective::kMinTime;
  if (min_time && !params.vehicle.valid()) {
    throw std::invalid_argument("GenerateTrajectory: objective min-time needs the vehicle");
  }
  if (!min_time && !(std::isfinite(params.max_speed) && std::isfinite(params.max_accel))) {
    throw std::invalid_argument("GenerateTrajectory: objective snap needs max_speed and max_accel");
  }
  const FlatnessLimits limits = min_time ? EffectiveLimits(params) : FlatnessLimits();
  // a singular system (degenerate waypoints or times) is an outcome like an infeasible one
  try {
    for (int round = 0;; ++round) {
      std::vector<Vec3>& waypoints = result.waypoints;
      if (min_time && round == 0) waypoints = CutLongSegments(waypoints, params.cruise_piece);
      if (params.use_corridors) waypoints = SplitForCorridors(waypoints, world.box_free);

      MinSnapProblem problem;
      problem.waypoints = waypoints;
      problem.durations =
          min_time
              ? MinTimeDurations(waypoints, limits, params)
              : RefineDurations(waypoints,
                                TrapezoidDurations(waypoints, params.max_speed, params.max_accel),
                                params.time_refinement_steps);
      problem.samples_per_segment = params.samples_per_segment;
      result.corridors.assign(problem.durations.size(), std::nullopt);
      if (params.use_corridors) {
        problem.corridors.resize(problem.durations.size());
        for (size_t i = 0; i + 1 < waypoints.size(); ++i) {
          result.corridors[i] =
              GrowCorridor(waypoints[i], waypoints[i + 1], world.box_free, params.corridor_growth);
          if (result.corridors[i]) {
            problem.corridors[i] = ShrinkCorridor(*result.corridors[i], waypoints[i],
                                                  waypoints[i + 1], params.corridor_margin);
          }
        }
      }
      // min-time: the corridors bend the solve away from the closed form's; a segment that now
      // asks too much gets its own time stretched and the problem is solved again, and the
      // fastest solve (once stretched to be feasible) is kept
      bool solved = true;
      double best_total = std::numeric_limits<double>::infinity();
      PiecewiseTrajectory best;
      for (int repair = 0;; ++repair) {
        if (params.use_corridors) {
          const MinSnapSolution solution = SolveMinSnapIpopt(problem, params.ipopt);
          result.stats.solver_message = solution.message;
          if (solution.status != SolveStatus::kSolved) {
            result.status = solution.status == SolveStatus::kInfeasible
                                ? TrajectoryStatus::kInfeasible
                                : TrajectoryStatus::kFailed;
            solved = best_total < std::numeric_limits<double>::infinity();
            break;
          }
          result.trajectory = solution.trajectory;
        } else {
          result.trajectory = SolveMinSnapClosedForm(problem);
          result.stats.solver_message = "closed form";
        }
        if (!min_time) break;
        std::vector<FeasibilityCheck> checks =
            CheckSegments(result.trajectory, limits, params.check_step);
        const double stretch = std::max(1.0, WorstScale(checks));
        if (result.trajectory.duration() * stretch < best_total) {
          best_total = result.trajectory.duration() * stretch;
          best = result.trajectory;
          best.ScaleTime(stretch);
        }
        if (stretch <= 1.0 || repair >= kMaxRepairs) break;
        for (FeasibilityCheck& check : checks) {
          check.scale = std::max(check.scale, kMinTimeTarget);  // stretch only
        }
        ScaleSegmentTimes(checks, &problem.durations);
      }
      if (min_time && solved) result.trajectory = best;
      if (!solved) break;
      if (min_time) {
        // the last word: the whole trajectory within the limits (a uniform stretch when a
        // repair left a point over; time scaling is monotone in every limit)
        for (int k = 0; k < 3; ++k) {
          const FeasibilityCheck worst =
              CheckFeasibility(result.trajectory, limits, params.check_step);
          if (worst.scale <= 1.0) break;
          result.trajectory.ScaleTime(worst.scale * 1.001);
        }
        result.stats.binding_limit = CheckFeasibility(result.trajectory, limits, params.check_step);
      } else {
        ScaleToLimits(params.max_speed, params.max_accel, params.check_step, &result.trajectory);
      }

      // collision-aware refinement: the segment that leaves free space gets its midpoint
      if (Refine(world, params, round, &waypoints, &result)) break;
    }
  } catch (const SingularSystem& e) {
    result.status = TrajectoryStatus::kFailed;
    result.stats.solver_message = e.what();
  }

  result.stats.segments = static_cast<int>(result.waypoints.size()) - 1;
  MeasureTrajectory(params, &result);
  result.stats.solve_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  return result;
}

TrajectoryResult ContinueTrajectory(const StartState& start, const std::vector<Vec3>& path,
                                    const TrajectoryWorld& world, const TrajectoryParams& params) {
  constexpr double kMaxContinuation = 600.0;  // [s]: longer is no continuation of a flight
  params.Validate();
  const auto begin = std::chrono::steady_clock::now();
  TrajectoryResult result;
  if (path.size() < 2) throw std::invalid_argument("ContinueTrajectory: path too short");
  const bool min_time = params.objective == TimeObjective::kMinTime && params.vehicle.valid();
  const FlatnessLimits limits = min_time ? EffectiveLimits(params) : FlatnessLimits();
  const double search_step = std::max(params.check_step, 0.025);  // [s]
  // the times' first guess: each leg's trapezoid at the speed and acceleration the vehicle
  // reaches (the start's own speed makes the first leg no slower than from rest)
  const double speed = min_time ? std::min(limits.max_speed, params.max_speed) : params.max_speed;
  const double accel = min_time ? std::min(kGravity * std::tan(limits.max_tilt), params.max_accel)
                                : params.max_accel;
  MinSnapProblem problem;
  problem.waypoints = CutLongSegments(WithoutNearRepeats(path, world), params.cruise_piece);
  problem.waypoints.front() = start.p_W;
  problem.start_velocity = start.v_W;
  problem.start_acceleration = start.a_W;
  problem.start_jerk = start.j_W;
  // after a refinement, the last feasible times with the split segment's time halved: most
  // often feasible at once, which spares the search
  std::vector<double> warm;
  try {
    for (int round = 0;; ++round) {
      const std::vector<double> guess =
          TrapezoidDurationsAlongLegs(problem.waypoints, speed, accel);
      // a start in motion may want the first guess's times shorter or longer: several starts
      // at a common factor, each with rounds of per-segment scaling (damped: the square root of
      // what each segment's check asks, both ways)
      bool feasible = false;
      for (const double factor : {0.0, 1.0, 0.6, 1.6, 3.0}) {
        if (factor == 0.0 && warm.empty()) continue;
        problem.durations = factor == 0.0 ? warm : guess;
        if (factor != 0.0) {
          for (double& t : problem.durations) t *= factor;
        }
        for (int k = 0; k < 8 && !feasible; ++k) {
          result.trajectory = SolveMinSnapClosedForm(problem);
          ++result.stats.solves;
          if (!min_time) {
            const double v = result.trajectory.MaxNorm(kVelocity, params.check_step) / speed;
            const double a = result.trajectory.MaxNorm(kAcceleration, params.check_step) / accel;
            const double scale = std::max(v, std::sqrt(a));
            feasible = scale <= 1.0;
            if (!feasible) {
              for (double& t : problem.durations) t *= scale * 1.01;
            }
            continue;
          }
          // searched on coarser samples (a replan's latency is mostly this), confirmed on the
          // check step
          const std::vector<FeasibilityCheck> checks =
              CheckSegments(result.trajectory, limits, search_step);
          feasible = WorstScale(checks) <= 1.0 &&
                     CheckFeasibility(result.trajectory, limits, params.check_step).ratio <= 1.0;
          if (feasible) break;
          // damped at first; then doubled, since near the fixed start a segment's check asks
          // for much less than it needs, and smaller steps crawl there
          for (size_t i = 0; i < checks.size(); ++i) {
            const double scale = std::max(checks[i].scale, checks[i].scale > 0.97 ? 1.01 : 0.0);
            if (scale > 1.0)
              problem.durations[i] *= (k < 2 ? std::sqrt(scale) : scale * scale) * 1.02;
          }
          // a start too fast for the room ahead overshoots whatever the times: next start
          if (std::accumulate(problem.durations.begin(), problem.durations.end(), 0.0) >
              kMaxContinuation) {
            break;
          }
        }
        if (feasible) break;
      }
      if (!feasible) {
        result.status = TrajectoryStatus::kInfeasible;
        result.stats.solver_message = "no feasible times from four starts";
        result.trajectory = PiecewiseTrajectory();
        break;
      }
      result.stats.solver_message = "closed form, continuing";
      const std::vector<Vec3> before = problem.waypoints;
      if (Refine(world, params, round, &problem.waypoints, &result)) break;
      size_t split = 0;  // the segment Refine split in two
      while (split + 1 < before.size() && before[split + 1] == problem.waypoints[split + 1]) {
        ++split;
      }
      warm = problem.durations;
      warm[split] *= 0.5;
      warm.insert(warm.begin() + static_cast<long>(split), warm[split]);
    }
  } catch (const SingularSystem& e) {
    result.status = TrajectoryStatus::kFailed;
    result.stats.solver_message = e.what();
  }
  result.waypoints = problem.waypoints;
  result.corridors.assign(problem.waypoints.size() - 1, std::nullopt);
  result.stats.segments = static_cast<int>(problem.waypoints.size()) - 1;
  if (min_time && result.status == TrajectoryStatus::kSolved) {
    result.stats.binding_limit = CheckFeasibility(result.trajectory, limits, params.check_step);
  }
  MeasureTrajectory(params, &result);
  result.stats.solve_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  return result;
}

}  // namespace aerobox
