#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

#include "geometry/ray_cast.h"

namespace aerobox {
namespace {

const Aabb kUnit{Vec3(1, -0.5, -0.5), Vec3(2, 0.5, 0.5)};

// The second method: march along the ray in 0.1 mm steps until a point lies in a box.
double Marched(const std::vector<Aabb>& boxes, const Vec3& o, const Vec3& d, double range) {
  for (double s = 0.0; s <= range; s += 1e-4) {
    for (const Aabb& box : boxes) {
      if (box.Contains(o + s * d)) return s;
    }
  }
  return range;
}

TEST_CASE("A ray enters a box where the slabs say, and misses it when it passes by") {
  CHECK(RayToBox(Vec3::Zero(), Vec3::UnitX(), kUnit) == doctest::Approx(1.0));
  CHECK(std::isinf(RayToBox(Vec3::Zero(), -Vec3::UnitX(), kUnit)));  // behind
  CHECK(std::isinf(RayToBox(Vec3(0, 1, 0), Vec3::UnitX(), kUnit)));  // parallel, beside
  CHECK(RayToBox(Vec3(1.5, 0, 0), Vec3::UnitY(), kUnit) == 0.0);     // from inside
  const Vec3 diagonal = Vec3(1, 0.4, 0).normalized();
  CHECK(RayToBox(Vec3::Zero(), diagonal, kUnit) == doctest::Approx(1.0 / diagonal.x()));
}

TEST_CASE("A ray leaves the bounds at the nearest face ahead and is capped at the range") {
  const Aabb bounds{Vec3(-1, -2, 0), Vec3(3, 2, 4)};
  CHECK(RayOutOf(Vec3(0, 0, 1), Vec3::UnitX(), bounds) == doctest::Approx(3.0));
  CHECK(RayOutOf(Vec3(0, 0, 1), -Vec3::UnitZ(), bounds) == doctest::Approx(1.0));
  CHECK(CastRay({}, bounds, Vec3(0, 0, 1), Vec3::UnitX(), 2.5) == doctest::Approx(2.5));
  CHECK(CastRay({kUnit}, bounds, Vec3(0, 0, 0.2), Vec3::UnitX(), 5.0) == doctest::Approx(1.0));
}

TEST_CASE("CastRay agrees with marching along the ray on random boxes to 0.1 mm") {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> where(0.0, 6.0), size(0.2, 1.5), unit(-1.0, 1.0);
  const Aabb bounds{Vec3(-1, -1, -1), Vec3(7, 7, 7)};
  std::vector<Aabb> boxes;
  for (int i = 0; i < 40; ++i) {
    const Vec3 min(where(rng), where(rng), where(rng));
    boxes.push_back({min, min + Vec3(size(rng), size(rng), size(rng))});
  }
  int hits = 0;
  for (int k = 0; k < 40; ++k) {
    const Vec3 o(where(rng), where(rng), where(rng));
    const Vec3 d = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
    const double range = std::min(4.0, RayOutOf(o, d, bounds));
    const double cast = CastRay(boxes, bounds, o, d, 4.0);
    CHECK(std::abs(cast - Marched(boxes, o, d, range)) < 2e-4);
    hits += cast < range;
  }
  CHECK(hits > 10);  // the check saw hits, not only misses
}

}  // namespace
}  // namespace aerobox
