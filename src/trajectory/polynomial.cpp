#include "trajectory/polynomial.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace aerobox {
namespace {

// k! / (k - r)!: the factor d^r/ds^r brings down in front of s^(k - r).
double FallingFactorial(int k, int r) {
  double f = 1.0;
  for (int i = 0; i < r; ++i) f *= k - i;
  return f;
}

}  // namespace

BasisRow Basis(double s, int derivative, double duration) {
  BasisRow row = BasisRow::Zero();
  // powers by products: this runs several times per simulation step
  double scale = 1.0;  // duration^-derivative
  for (int i = 0; i < derivative; ++i) scale /= duration;
  double power = 1.0;  // s^(k - derivative)
  for (int k = derivative; k < kCoefficients; ++k) {
    row[k] = FallingFactorial(k, derivative) * power * scale;
    power *= s;
  }
  return row;
}

PolynomialSegment::PolynomialSegment(Eigen::MatrixXd coefficients, double duration)
    : coefficients_(std::move(coefficients)), duration_(duration) {
  if (coefficients_.cols() != kCoefficients || coefficients_.rows() < 1) {
    throw std::invalid_argument("PolynomialSegment: coefficients must be dimension x 8");
  }
  if (!(duration_ > 0 && std::isfinite(duration_))) {
    throw std::invalid_argument("PolynomialSegment: duration must be positive");
  }
}

Eigen::VectorXd PolynomialSegment::Evaluate(double t, int derivative) const {
  const double s = std::clamp(t / duration_, 0.0, 1.0);
  return coefficients_ * Basis(s, derivative, duration_).transpose();
}

Vec3 PolynomialSegment::Evaluate3(double t, int derivative) const {
  if (coefficients_.rows() != 3) throw std::logic_error("PolynomialSegment: not 3-dimensional");
  const double s = std::clamp(t / duration_, 0.0, 1.0);
  const BasisRow basis = Basis(s, derivative, duration_);
  Vec3 value = Vec3::Zero();
  for (int k = derivative; k < kCoefficients; ++k) value += coefficients_.col(k) * basis[k];
  return value;
}

double PolynomialSegment::SnapCost() const {
  // integral_0^T (d^4p/dt^4)^2 dt = T^-7 integral_0^1 (d^4p/ds^4)^2 ds, and
  // integral_0^1 s^(j-4) s^(k-4) ds = 1 / (j + k - 7)
  double cost = 0.0;
  for (int j = kSnap; j < kCoefficients; ++j) {
    for (int k = kSnap; k < kCoefficients; ++k) {
      const double q = FallingFactorial(j, kSnap) * FallingFactorial(k, kSnap) / (j + k - 7);
      cost += q * coefficients_.col(j).dot(coefficients_.col(k));
    }
  }
  return cost / std::pow(duration_, 7);
}

PiecewiseTrajectory::PiecewiseTrajectory(std::vector<PolynomialSegment> segments)
    : segments_(std::move(segments)) {}

double PiecewiseTrajectory::duration() const {
  double total = 0.0;
  for (const PolynomialSegment& segment : segments_) total += segment.duration();
  return total;
}

std::vector<double> PiecewiseTrajectory::KnotTimes() const {
  std::vector<double> knots = {0.0};
  for (const PolynomialSegment& segment : segments_)
    knots.push_back(knots.back() + segment.duration());
  return knots;
}

std::vector<double> PiecewiseTrajectory::SegmentDurations() const {
  std::vector<double> durations;
  for (const PolynomialSegment& segment : segments_) durations.push_back(segment.duration());
  return durations;
}

Eigen::VectorXd PiecewiseTrajectory::Evaluate(double t, int derivative) const {
  if (segments_.empty()) throw std::logic_error("PiecewiseTrajectory: empty");
  t = std::max(t, 0.0);
  for (size_t i = 0; i + 1 < segments_.size(); ++i) {
    if (t < segments_[i].duration()) return segments_[i].Evaluate(t, derivative);
    t -= segments_[i].duration();
  }
  return segments_.back().Evaluate(t, derivative);
}

Vec3 PiecewiseTrajectory::Evaluate3(double t, int derivative) const {
  if (segments_.empty()) throw std::logic_error("PiecewiseTrajectory: empty");
  t = std::max(t, 0.0);
  for (size_t i = 0; i + 1 < segments_.size(); ++i) {
    if (t < segments_[i].duration()) return segments_[i].Evaluate3(t, derivative);
    t -= segments_[i].duration();
  }
  return segments_.back().Evaluate3(t, derivative);
}

double PiecewiseTrajectory::SnapCost() const {
  double cost = 0.0;
  for (const PolynomialSegment& segment : segments_) cost += segment.SnapCost();
  return cost;
}

void PiecewiseTrajectory::ScaleTime(double factor) {
  for (PolynomialSegment& segment : segments_) segment.ScaleTime(factor);
}

double PiecewiseTrajectory::MaxNorm(int derivative, double dt) const {
  double peak = 0.0;
  for (const PolynomialSegment& segment : segments_) {
    const int steps = std::max(1, static_cast<int>(std::ceil(segment.duration() / dt)));
    for (int i = 0; i <= steps; ++i) {
      peak = std::max(peak, segment.Evaluate(segment.duration() * i / steps, derivative).norm());
    }
  }
  return peak;
}

}  // namespace aerobox
