#include "disturbance/wind.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/number_format.h"

namespace aerobox {
namespace {

constexpr double kFeet = 0.3048;  // [m]
constexpr double kPi = 3.14159265358979323846;

// The factor L of a 2x2 covariance Q = L L' (lower triangular); rounding may leave Q a hair
// from positive definite when a step is tiny against the correlation time.
Eigen::Matrix2d Factor(const Eigen::Matrix2d& q) {
  Eigen::Matrix2d l = Eigen::Matrix2d::Zero();
  l(0, 0) = std::sqrt(std::max(q(0, 0), 0.0));
  l(1, 0) = l(0, 0) > 0 ? q(1, 0) / l(0, 0) : 0.0;
  l(1, 1) = std::sqrt(std::max(q(1, 1) - l(1, 0) * l(1, 0), 0.0));
  return l;
}

}  // namespace

Vec3 Gust::At(double t) const {
  const double s = t - start;
  if (s <= 0 || s >= duration) return Vec3::Zero();
  const double edge = std::min(s, duration - s);  // [s] from the nearer end
  const double shape = edge >= rise ? 1.0 : 0.5 * (1.0 - std::cos(kPi * edge / rise));
  return peak * shape * direction.normalized();
}

bool WindParams::Enabled() const {
  return mean.squaredNorm() > 0 || !gusts.empty() || turbulence != Turbulence::kNone;
}

void Gust::Describe(Archive& a) {
  a.Number({"start", "s", "of flight time"}, &start, 0, 1e5);
  a.Number({"rise", "s", "from zero to the peak, and from the peak back to zero"}, &rise, 1e-3,
           1e4);
  a.Number({"duration", "s", "in all, rise and fall included; at least twice the rise"}, &duration,
           2e-3, 1e5);
  a.Number({"peak", "m/s", "the gust's speed at its peak"}, &peak, 0, 50);
  a.Vector({"direction", "", "world frame; any length but zero"}, &direction, -1e3, 1e3);
}

void WindParams::Describe(Archive& a) {
  a.Vector({"mean", "m/s", "the mean wind, world frame"}, &mean, -50, 50);
  a.Enum({"turbulence", "", "Dryden turbulence (MIL-F-8785C) on the mean wind, or none"},
         &turbulence, {{Turbulence::kDryden, "dryden"}, {Turbulence::kNone, "none"}});
  a.Vector({"intensity", "m/s",
            "the turbulence's standard deviations: along the mean wind, across it, vertical"},
           &intensity, 0, 20);
  a.Number({"min_airspeed", "m/s", "below this airspeed the turbulence's filters use this one"},
           &min_airspeed, 0.01, 100);
}

void WindParams::Validate() const {
  ValidateFields(*this, "wind");
  for (size_t i = 0; i < gusts.size(); ++i) {
    const Gust& g = gusts[i];
    const std::string field = "wind.gusts[" + std::to_string(i) + "]";
    ValidateFields(g, field);
    if (!(g.duration >= 2 * g.rise)) {
      throw std::invalid_argument(field + ".duration: expected at least twice the rise (" +
                                  FormatNumber(2 * g.rise) + " s), got " +
                                  FormatNumber(g.duration));
    }
    if (!(g.direction.norm() > 1e-9)) {
      throw std::invalid_argument(field + ".direction: expected a non-zero vector");
    }
  }
}

Vec3 DrydenScaleLengths(double height) {
  const double h = std::clamp(height, 1.0, 1000 * kFeet) / kFeet;  // [ft]
  const double horizontal = h / std::pow(0.177 + 0.000823 * h, 1.2);
  return Vec3(horizontal, horizontal, h) * kFeet;
}

Vec3 DrydenIntensities(double wind_20ft, double height) {
  const double h = std::clamp(height, 1.0, 1000 * kFeet) / kFeet;  // [ft]
  const double w = 0.1 * std::abs(wind_20ft);
  const double horizontal = w / std::pow(0.177 + 0.000823 * h, 0.4);
  return Vec3(horizontal, horizontal, w);
}

DrydenTurbulence::DrydenTurbulence(const Vec3& intensity, std::uint64_t seed)
    : intensity_(intensity), rng_(seed) {
  // the stationary distribution: unit variance, uncorrelated (the normalisation's point)
  u_ = normal_(rng_);
  v_ = Eigen::Vector2d(normal_(rng_), normal_(rng_));
  w_ = Eigen::Vector2d(normal_(rng_), normal_(rng_));
  current_ = Vec3(intensity_.x() * u_, intensity_.y() * 0.5 * (v_[0] + std::sqrt(3.0) * v_[1]),
                  intensity_.z() * 0.5 * (w_[0] + std::sqrt(3.0) * w_[1]));
}

Vec3 DrydenTurbulence::Step(double dt, double airspeed, double height) {
  const Vec3 length = DrydenScaleLengths(height);
  // u: H(s) = sigma sqrt(2 L / (pi V)) / (1 + T s), T = L / V: an Ornstein-Uhlenbeck process,
  // exactly z+ = e^-x z + sqrt(1 - e^-2x) n with x = dt / T
  {
    const double x = dt * airspeed / length.x();
    const double decay = std::exp(-x);
    u_ = decay * u_ + std::sqrt(std::max(0.0, 1.0 - decay * decay)) * normal_(rng_);
  }
  // v and w: H(s) = sigma sqrt(L / (pi V)) (1 + sqrt(3) T s) / (1 + T s)^2. In the states
  // x1, x2 = x1' of 1 / (1 + T s)^2 scaled to unit stationary variance, the transition is
  // e^-x [[1 + x, x], [-x, 1 - x]], the covariance a step adds is I - Phi Phi', and the output
  // is sigma (z1 + sqrt(3) z2) / 2
  const auto second_order = [&](double scale_length, Eigen::Vector2d* z) {
    const double x = dt * airspeed / scale_length;
    Eigen::Matrix2d phi;
    phi << 1 + x, x, -x, 1 - x;
    phi *= std::exp(-x);
    const Eigen::Matrix2d added = Eigen::Matrix2d::Identity() - phi * phi.transpose();
    *z = phi * *z + Factor(added) * Eigen::Vector2d(normal_(rng_), normal_(rng_));
    return 0.5 * ((*z)[0] + std::sqrt(3.0) * (*z)[1]);
  };
  const double v = second_order(length.y(), &v_);
  const double w = second_order(length.z(), &w_);
  current_ = Vec3(intensity_.x() * u_, intensity_.y() * v, intensity_.z() * w);
  return current_;
}

WindField::WindField(const WindParams& params, std::uint64_t seed)
    : params_(params), turbulence_(params.intensity, seed) {
  params_.Validate();
  Vec3 along(params.mean.x(), params.mean.y(), 0.0);
  along = along.norm() > 1e-9 ? along.normalized() : Vec3::UnitX();
  R_WT_.col(0) = along;
  R_WT_.col(1) = Vec3::UnitZ().cross(along);
  R_WT_.col(2) = Vec3::UnitZ();
  current_ = params_.mean;
  for (const Gust& g : params_.gusts) current_ += g.At(0.0);
  if (params_.turbulence == Turbulence::kDryden) current_ += R_WT_ * turbulence_.current();
}

Vec3 WindField::Step(double t, double dt, double height, const Vec3& v_W) {
  Vec3 steady = params_.mean;
  for (const Gust& g : params_.gusts) steady += g.At(t);
  current_ = steady;
  if (params_.turbulence == Turbulence::kDryden) {
    const double airspeed = std::max(params_.min_airspeed, (v_W - steady).norm());
    current_ += R_WT_ * turbulence_.Step(dt, airspeed, height);
  }
  return current_;
}

}  // namespace aerobox
