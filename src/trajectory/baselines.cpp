#include "trajectory/baselines.h"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <cmath>
#include <stdexcept>

namespace aerobox {
namespace {

void Check(const std::vector<Vec3>& waypoints, const std::vector<double>& durations) {
  if (waypoints.size() < 2 || durations.size() + 1 != waypoints.size()) {
    throw std::invalid_argument("baseline trajectory: need n + 1 waypoints for n durations");
  }
  for (const double t : durations) {
    if (!(t > 0 && std::isfinite(t))) {
      throw std::invalid_argument("baseline trajectory: durations must be positive");
    }
  }
}

// The segment of `degree` (3, 5 or 7) whose derivatives 0 .. (degree - 1) / 2 at its two ends
// are the columns of `start` and `end` (3 x k, physical time).
PolynomialSegment SegmentFromEnds(const Eigen::MatrixXd& start, const Eigen::MatrixXd& end,
                                  double duration) {
  const int k = static_cast<int>(start.cols());
  const int n = 2 * k;  // coefficients used
  Eigen::MatrixXd rows(n, n);
  Eigen::MatrixXd values(n, 3);
  for (int r = 0; r < k; ++r) {
    rows.row(r) = Basis(0.0, r, duration).head(n);
    rows.row(k + r) = Basis(1.0, r, duration).head(n);
    values.row(r) = start.col(r).transpose();
    values.row(k + r) = end.col(r).transpose();
  }
  Eigen::MatrixXd coefficients = Eigen::MatrixXd::Zero(3, kCoefficients);
  coefficients.leftCols(n) = rows.partialPivLu().solve(values).transpose();
  return PolynomialSegment(coefficients, duration);
}

}  // namespace

const char* ToString(TrajectoryMethod method) {
  switch (method) {
    case TrajectoryMethod::kMinSnap:
      return "minsnap";
    case TrajectoryMethod::kQuintic:
      return "quintic";
    case TrajectoryMethod::kCubic:
      return "cubic";
    case TrajectoryMethod::kSepticFull:
      return "septic-full";
  }
  return "?";
}

std::optional<TrajectoryMethod> ParseTrajectoryMethod(std::string_view name) {
  for (const TrajectoryMethod m : {TrajectoryMethod::kMinSnap, TrajectoryMethod::kQuintic,
                                   TrajectoryMethod::kCubic, TrajectoryMethod::kSepticFull}) {
    if (name == ToString(m)) return m;
  }
  return std::nullopt;
}

PiecewiseTrajectory QuinticTrajectory(const std::vector<Vec3>& waypoints,
                                      const std::vector<double>& durations) {
  Check(waypoints, durations);
  const size_t n = durations.size();
  // velocity and acceleration at each waypoint by the stated rule
  std::vector<Vec3> v(n + 1, Vec3::Zero()), a(n + 1, Vec3::Zero());
  for (size_t i = 1; i < n; ++i) {
    const Vec3 in = (waypoints[i] - waypoints[i - 1]) / durations[i - 1];
    const Vec3 out = (waypoints[i + 1] - waypoints[i]) / durations[i];
    v[i] = 0.5 * (in + out);
    a[i] = (out - in) / (0.5 * (durations[i - 1] + durations[i]));
  }
  std::vector<PolynomialSegment> segments;
  for (size_t i = 0; i < n; ++i) {
    Eigen::MatrixXd start(3, 3), end(3, 3);
    start << waypoints[i], v[i], a[i];
    end << waypoints[i + 1], v[i + 1], a[i + 1];
    segments.push_back(SegmentFromEnds(start, end, durations[i]));
  }
  return PiecewiseTrajectory(segments);
}

PiecewiseTrajectory CubicSplineTrajectory(const std::vector<Vec3>& waypoints,
                                          const std::vector<double>& durations) {
  Check(waypoints, durations);
  const size_t n = durations.size();
  std::vector<Vec3> v(n + 1, Vec3::Zero());
  if (n > 1) {
    // acceleration continuous at interior waypoint i, with Hermite cubics on both sides:
    // (2/Ta) v[i-1] + 4 (1/Ta + 1/Tb) v[i] + (2/Tb) v[i+1]
    //   = 6 (p[i] - p[i-1]) / Ta^2 + 6 (p[i+1] - p[i]) / Tb^2,   v[0] = v[n] = 0
    const int m = static_cast<int>(n) - 1;
    Eigen::MatrixXd lhs = Eigen::MatrixXd::Zero(m, m);
    Eigen::MatrixXd rhs(m, 3);
    for (int r = 0; r < m; ++r) {
      const size_t i = r + 1;
      const double ta = durations[i - 1], tb = durations[i];
      lhs(r, r) = 4.0 / ta + 4.0 / tb;
      if (r > 0) lhs(r, r - 1) = 2.0 / ta;
      if (r + 1 < m) lhs(r, r + 1) = 2.0 / tb;
      rhs.row(r) = (6.0 * (waypoints[i] - waypoints[i - 1]) / (ta * ta) +
                    6.0 * (waypoints[i + 1] - waypoints[i]) / (tb * tb))
                       .transpose();
    }
    const Eigen::MatrixXd solved = lhs.partialPivLu().solve(rhs);
    for (int r = 0; r < m; ++r) v[r + 1] = solved.row(r).transpose();
  }
  std::vector<PolynomialSegment> segments;
  for (size_t i = 0; i < n; ++i) {
    Eigen::MatrixXd start(3, 2), end(3, 2);
    start << waypoints[i], v[i];
    end << waypoints[i + 1], v[i + 1];
    segments.push_back(SegmentFromEnds(start, end, durations[i]));
  }
  return PiecewiseTrajectory(segments);
}

PiecewiseTrajectory SepticFullTrajectory(const std::vector<Vec3>& waypoints,
                                         const std::vector<double>& durations) {
  Check(waypoints, durations);
  const int n = static_cast<int>(durations.size());
  const int size = kCoefficients * n;
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(size, 3);
  int row = 0;
  const auto add = [&](int segment, double s, int derivative, double sign) {
    const BasisRow b = Basis(s, derivative, durations[segment]);
    for (int k = 0; k < kCoefficients; ++k) {
      if (b[k] != 0.0) entries.emplace_back(row, kCoefficients * segment + k, sign * b[k]);
    }
  };
  for (int i = 0; i < n; ++i) {  // positions at both ends of every segment
    add(i, 0.0, kPosition, 1.0);
    rhs.row(row++) = waypoints[i].transpose();
    add(i, 1.0, kPosition, 1.0);
    rhs.row(row++) = waypoints[i + 1].transpose();
  }
  for (int i = 1; i < n; ++i) {  // derivatives 1-6 continuous at interior waypoints
    for (int r = 1; r <= 6; ++r) {
      add(i - 1, 1.0, r, 1.0);
      add(i, 0.0, r, -1.0);
      ++row;
    }
  }
  for (int r = kVelocity; r <= kJerk; ++r) {  // rest at both ends
    add(0, 0.0, r, 1.0);
    ++row;
    add(n - 1, 1.0, r, 1.0);
    ++row;
  }
  Eigen::SparseMatrix<double> system(size, size);
  system.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(system);
  if (lu.info() != Eigen::Success) {
    throw std::runtime_error("septic-full: the linear system is singular");
  }
  const Eigen::MatrixXd coefficients = lu.solve(rhs);
  std::vector<PolynomialSegment> segments;
  for (int i = 0; i < n; ++i) {
    segments.emplace_back(coefficients.middleRows(kCoefficients * i, kCoefficients).transpose(),
                          durations[i]);
  }
  return PiecewiseTrajectory(segments);
}

PiecewiseTrajectory BaselineTrajectory(TrajectoryMethod method, const std::vector<Vec3>& waypoints,
                                       const std::vector<double>& durations) {
  switch (method) {
    case TrajectoryMethod::kQuintic:
      return QuinticTrajectory(waypoints, durations);
    case TrajectoryMethod::kCubic:
      return CubicSplineTrajectory(waypoints, durations);
    case TrajectoryMethod::kSepticFull:
      return SepticFullTrajectory(waypoints, durations);
    case TrajectoryMethod::kMinSnap:
      break;
  }
  throw std::invalid_argument("BaselineTrajectory: minsnap is not a baseline");
}

}  // namespace aerobox
