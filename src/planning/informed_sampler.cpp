#include "planning/informed_sampler.h"

#include <cmath>
#include <limits>

namespace aerobox {

InformedSampler::InformedSampler(const Vec3& start, const Vec3& goal, const Aabb& bounds)
    : centre_(0.5 * (start + goal)), min_cost_((goal - start).norm()), bounds_(bounds) {
  // any rotation taking x to the start -> goal direction will do
  const Vec3 axis = min_cost_ > 0 ? Vec3((goal - start) / min_cost_) : Vec3::UnitX();
  rotation_ = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitX(), axis).toRotationMatrix();
}

Vec3 InformedSampler::Sample(double best_cost, std::mt19937_64* rng) const {
  if (!std::isfinite(best_cost)) return SampleBounds(rng);
  // which is smaller, the box or the spheroid's bounding box? sample the smaller one and
  // reject what lies outside the other
  const double a = 0.5 * best_cost;
  const double b = 0.5 * std::sqrt(std::max(0.0, best_cost * best_cost - min_cost_ * min_cost_));
  const double spheroid_volume = 4.0 / 3.0 * M_PI * a * b * b;
  const double box_volume = bounds_.Size().prod();
  constexpr int kTries = 1000;
  for (int i = 0; i < kTries; ++i) {
    if (spheroid_volume < box_volume) {
      const Vec3 x = SampleSpheroid(best_cost, rng);
      if (bounds_.Contains(x)) return x;
    } else {
      const Vec3 x = SampleBounds(rng);
      const Vec3 local = rotation_.transpose() * (x - centre_);
      const Vec3 scaled(local.x() / a, local.y() / std::max(b, 1e-12),
                        local.z() / std::max(b, 1e-12));
      if (scaled.squaredNorm() <= 1.0) return x;
    }
  }
  return SampleSpheroid(best_cost, rng).cwiseMax(bounds_.min).cwiseMin(bounds_.max);
}

Vec3 InformedSampler::SampleBounds(std::mt19937_64* rng) const {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Vec3 x;
  for (int k = 0; k < 3; ++k)
    x[k] = bounds_.min[k] + unit(*rng) * (bounds_.max[k] - bounds_.min[k]);
  return x;
}

Vec3 InformedSampler::SampleSpheroid(double best_cost, std::mt19937_64* rng) const {
  // uniform in the unit ball: a Gaussian direction and a radius u^(1/3)
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Vec3 ball(gauss(*rng), gauss(*rng), gauss(*rng));
  ball *= std::cbrt(unit(*rng)) / std::max(ball.norm(), std::numeric_limits<double>::min());
  const double a = 0.5 * best_cost;
  const double b = 0.5 * std::sqrt(std::max(0.0, best_cost * best_cost - min_cost_ * min_cost_));
  return centre_ + rotation_ * Vec3(a * ball.x(), b * ball.y(), b * ball.z());
}

}  // namespace aerobox
