#include "trajectory/trajectory_generator.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "common/number_format.h"
#include "trajectory/time_allocation.h"

namespace aerobox {
namespace {

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

}  // namespace

void TrajectoryParams::Validate() const {
  const auto fail = [](const char* field, double value) {
    throw std::invalid_argument(std::string("TrajectoryParams.") + field +
                                " out of range: " + FormatNumber(value));
  };
  if (!(max_speed > 0 && std::isfinite(max_speed))) fail("max_speed", max_speed);
  if (!(max_accel > 0 && std::isfinite(max_accel))) fail("max_accel", max_accel);
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

TrajectoryResult GenerateTrajectory(const std::vector<Vec3>& path, const TrajectoryWorld& world,
                                    const TrajectoryParams& params) {
  params.Validate();
  const auto begin = std::chrono::steady_clock::now();
  TrajectoryResult result;
  result.waypoints = WithoutNearRepeats(path, world);
  if (result.waypoints.size() < 2)
    throw std::invalid_argument("GenerateTrajectory: path too short");

  // a singular system (degenerate waypoints or times) is an outcome like an infeasible one
  try {
    for (int round = 0;; ++round) {
      std::vector<Vec3>& waypoints = result.waypoints;
      if (params.use_corridors) waypoints = SplitForCorridors(waypoints, world.box_free);

      MinSnapProblem problem;
      problem.waypoints = waypoints;
      problem.durations = RefineDurations(
          waypoints, TrapezoidDurations(waypoints, params.max_speed, params.max_accel),
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
        const MinSnapSolution solution = SolveMinSnapIpopt(problem, params.ipopt);
        result.stats.solver_message = solution.message;
        if (solution.status != SolveStatus::kSolved) {
          result.status = solution.status == SolveStatus::kInfeasible
                              ? TrajectoryStatus::kInfeasible
                              : TrajectoryStatus::kFailed;
          break;
        }
        result.trajectory = solution.trajectory;
      } else {
        result.trajectory = SolveMinSnapClosedForm(problem);
        result.stats.solver_message = "closed form";
      }
      ScaleToLimits(params.max_speed, params.max_accel, params.check_step, &result.trajectory);

      // collision-aware refinement: the segment that leaves free space gets its midpoint
      const std::optional<double> hit =
          FirstCollisionTime(result.trajectory, world, params.check_step);
      if (!hit) {
        result.status = TrajectoryStatus::kSolved;
        break;
      }
      if (round >= params.max_refinements) {
        result.status = TrajectoryStatus::kCollides;
        break;
      }
      const std::vector<double> knots = result.trajectory.KnotTimes();
      size_t segment = 0;
      while (segment + 2 < knots.size() && knots[segment + 1] < *hit) ++segment;
      waypoints.insert(waypoints.begin() + static_cast<long>(segment) + 1,
                       0.5 * (waypoints[segment] + waypoints[segment + 1]));
      ++result.stats.refinements;
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

}  // namespace aerobox
