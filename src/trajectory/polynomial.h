// Polynomial segments and piecewise trajectories in any dimension.
//
// A segment of duration T is p(t) = sum_k c_k s^k with s = t / T in [0, 1] (normalised time keeps
// the coefficients of long and short segments on one scale); its r-th time derivative is
// sum_k c_k k!/(k-r)! s^(k-r) / T^r.
#pragma once

#include <vector>

#include "common/types.h"

namespace aerobox {

// Named derivative orders (no bare 4 for snap).
enum Derivative : int {
  kPosition = 0,
  kVelocity = 1,
  kAcceleration = 2,
  kJerk = 3,
  kSnap = 4,
};

inline constexpr int kPolynomialDegree = 7;  // minimum snap needs degree 2 * 4 - 1
inline constexpr int kCoefficients = kPolynomialDegree + 1;

using BasisRow = Eigen::Matrix<double, 1, kCoefficients>;

// d^r/dt^r of (1, s, s^2, ..., s^7) at s in [0, 1], for a segment of duration T [s].
BasisRow Basis(double s, int derivative, double duration);

class PolynomialSegment {
 public:
  // coefficients: one row per dimension, kCoefficients columns (normalised time).
  PolynomialSegment(Eigen::MatrixXd coefficients, double duration);

  int dimension() const { return static_cast<int>(coefficients_.rows()); }
  double duration() const { return duration_; }
  const Eigen::MatrixXd& coefficients() const { return coefficients_; }

  // The derivative of the given order at local time t in [0, duration] (clamped).
  Eigen::VectorXd Evaluate(double t, int derivative) const;
  // The same for a 3-dimensional segment, without allocating (per simulation step).
  Vec3 Evaluate3(double t, int derivative) const;

  // integral over the segment of |snap|^2 [m^2/s^7], exactly.
  double SnapCost() const;

  // The same path in `factor` times the time (speeds / factor, accelerations / factor^2).
  void ScaleTime(double factor) { duration_ *= factor; }

 private:
  Eigen::MatrixXd coefficients_;
  double duration_;
};

class PiecewiseTrajectory {
 public:
  PiecewiseTrajectory() = default;
  explicit PiecewiseTrajectory(std::vector<PolynomialSegment> segments);

  bool empty() const { return segments_.empty(); }
  const std::vector<PolynomialSegment>& segments() const { return segments_; }
  double duration() const;
  // Start times of the segments and the end time: segments().size() + 1 knots [s].
  std::vector<double> KnotTimes() const;
  // Each segment's duration [s], in order.
  std::vector<double> SegmentDurations() const;

  // The derivative at time t [s] from the start; t outside [0, duration] is clamped.
  Eigen::VectorXd Evaluate(double t, int derivative) const;
  // The same for a 3-dimensional trajectory, without allocating (per simulation step).
  Vec3 Evaluate3(double t, int derivative) const;

  // Sum of the segments' snap costs.
  double SnapCost() const;
  void ScaleTime(double factor);

  // Largest |velocity| and |acceleration| over samples every `dt` seconds (and the ends).
  double MaxNorm(int derivative, double dt) const;

 private:
  std::vector<PolynomialSegment> segments_;
};

}  // namespace aerobox
