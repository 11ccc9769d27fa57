#include "trajectory/time_allocation.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "trajectory/min_snap.h"

namespace aerobox {

double TrapezoidTime(double length, double max_speed, double max_accel) {
  const double ramp = max_speed * max_speed / max_accel;  // distance to speed up and slow down
  if (length >= ramp) return length / max_speed + max_speed / max_accel;
  return 2.0 * std::sqrt(length / max_accel);
}

std::vector<double> TrapezoidDurations(const std::vector<Vec3>& waypoints, double max_speed,
                                       double max_accel) {
  std::vector<double> durations;
  for (size_t i = 1; i < waypoints.size(); ++i) {
    durations.push_back(
        TrapezoidTime((waypoints[i] - waypoints[i - 1]).norm(), max_speed, max_accel));
  }
  return durations;
}

namespace {

// Time [s] to cover the first `s` metres of a rest-to-rest trapezoid of `length` [m].
double TrapezoidTimeAt(double s, double length, double max_speed, double max_accel) {
  s = std::clamp(s, 0.0, length);
  // the peak speed: the limit, or what a triangle reaches at the middle
  const double peak = std::min(max_speed, std::sqrt(max_accel * length));
  const double ramp = 0.5 * peak * peak / max_accel;  // [m] to speed up (and to slow down)
  const double t_ramp = peak / max_accel;
  if (s <= ramp) return std::sqrt(2.0 * s / max_accel);
  const double cruise_end = length - ramp;
  if (s <= cruise_end) return t_ramp + (s - ramp) / peak;
  const double total = 2.0 * t_ramp + (cruise_end - ramp) / peak;
  return total - std::sqrt(2.0 * (length - s) / max_accel);
}

}  // namespace

std::vector<double> TrapezoidDurationsAlongLegs(const std::vector<Vec3>& waypoints,
                                                double max_speed, double max_accel) {
  std::vector<double> durations;
  size_t first = 0;  // the leg's first segment
  while (first + 1 < waypoints.size()) {
    // the leg: consecutive segments along one straight line
    const Vec3 direction = (waypoints[first + 1] - waypoints[first]).normalized();
    size_t last = first + 1;  // the leg's end waypoint
    while (last + 1 < waypoints.size() &&
           (waypoints[last + 1] - waypoints[last]).normalized().dot(direction) > 1.0 - 1e-9) {
      ++last;
    }
    const double length = (waypoints[last] - waypoints[first]).norm();
    double s = 0.0;
    for (size_t i = first; i < last; ++i) {
      const double next = s + (waypoints[i + 1] - waypoints[i]).norm();
      durations.push_back(std::max(1e-3, TrapezoidTimeAt(next, length, max_speed, max_accel) -
                                             TrapezoidTimeAt(s, length, max_speed, max_accel)));
      s = next;
    }
    first = last;
  }
  return durations;
}

namespace {

// The snap cost of a segment with the same position, velocity, acceleration and jerk at its two
// ends as `segment`, lasting `duration` [s].
double SnapCostWithEnds(const PolynomialSegment& segment, double duration) {
  Eigen::Matrix<double, kCoefficients, kCoefficients> ends;
  Eigen::MatrixXd values(kCoefficients, segment.dimension());
  for (int r = 0; r < kCoefficients / 2; ++r) {
    ends.row(r) = Basis(0.0, r, duration);
    ends.row(kCoefficients / 2 + r) = Basis(1.0, r, duration);
    values.row(r) = segment.Evaluate(0.0, r).transpose();
    values.row(kCoefficients / 2 + r) = segment.Evaluate(segment.duration(), r).transpose();
  }
  const Eigen::MatrixXd coefficients = ends.partialPivLu().solve(values).transpose();
  return PolynomialSegment(coefficients, duration).SnapCost();
}

}  // namespace

std::vector<double> SnapCostGradient(const PiecewiseTrajectory& trajectory) {
  std::vector<double> gradient;
  for (const PolynomialSegment& segment : trajectory.segments()) {
    const double h = 1e-5 * segment.duration();  // central differences of one segment's cost
    gradient.push_back((SnapCostWithEnds(segment, segment.duration() + h) -
                        SnapCostWithEnds(segment, segment.duration() - h)) /
                       (2.0 * h));
  }
  return gradient;
}

std::vector<double> RefineDurations(const std::vector<Vec3>& waypoints,
                                    std::vector<double> durations, int iterations,
                                    DurationGradient method) {
  const size_t n = durations.size();
  if (n < 2) return durations;
  const std::vector<double> floor_times = [&] {
    std::vector<double> f;
    for (const double t : durations) f.push_back(0.05 * t);
    return f;
  }();
  const auto solve = [&waypoints](const std::vector<double>& times) {
    MinSnapProblem problem;
    problem.waypoints = waypoints;
    problem.durations = times;
    return SolveMinSnapClosedForm(problem);
  };
  PiecewiseTrajectory optimum = solve(durations);
  double current = optimum.SnapCost();
  const double total = std::accumulate(durations.begin(), durations.end(), 0.0);
  double step = 0.1 * total / n;  // [s] of the first move along the normalised gradient
  for (int iteration = 0; iteration < iterations && step > 1e-4 * total / n; ++iteration) {
    // the gradient, projected onto "the sum stays the same"
    std::vector<double> gradient;
    if (method == DurationGradient::kEnvelope) {
      gradient = SnapCostGradient(optimum);
    } else {
      for (size_t i = 0; i < n; ++i) {
        std::vector<double> moved = durations;
        const double h = 1e-4 * durations[i];
        moved[i] += h;
        gradient.push_back((solve(moved).SnapCost() - current) / h);
      }
    }
    const double mean = std::accumulate(gradient.begin(), gradient.end(), 0.0) / n;
    double norm = 0.0;
    for (double& g : gradient) {
      g -= mean;
      norm += g * g;
    }
    norm = std::sqrt(norm);
    if (norm == 0.0) break;
    // backtracking: halve the step until the cost goes down (or give up on this direction)
    while (step > 1e-4 * total / n) {
      std::vector<double> trial = durations;
      bool valid = true;
      for (size_t i = 0; i < n; ++i) {
        trial[i] -= step * gradient[i] / norm;
        valid = valid && trial[i] >= floor_times[i];
      }
      if (!valid) {
        step *= 0.5;
        continue;
      }
      PiecewiseTrajectory moved = solve(trial);
      const double trial_cost = moved.SnapCost();
      if (trial_cost < current) {
        durations = trial;
        optimum = std::move(moved);
        current = trial_cost;
        step *= 1.5;
        break;
      }
      step *= 0.5;
    }
  }
  return durations;
}

double ScaleToLimits(double max_speed, double max_accel, double dt,
                     PiecewiseTrajectory* trajectory) {
  const double speed = trajectory->MaxNorm(kVelocity, dt);
  const double accel = trajectory->MaxNorm(kAcceleration, dt);
  const double factor = std::max(speed / max_speed, std::sqrt(accel / max_accel));
  if (factor > 0 && std::isfinite(factor)) trajectory->ScaleTime(factor);
  return factor;
}

}  // namespace aerobox
