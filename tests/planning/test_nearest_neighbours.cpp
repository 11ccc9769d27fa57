#include <doctest/doctest.h>

#include <algorithm>
#include <random>

#include "planning/nearest_neighbours.h"

namespace aerobox {

TEST_CASE("k nearest: exactly the brute-force set, for small and large k, as points are added") {
  std::vector<Vec3> points;
  NearestNeighbours index(&points);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> where(0.0, 10.0);
  std::vector<size_t> found;
  std::vector<double> d2;
  for (int n = 1; n <= 3000; ++n) {
    // clustered points too, as informed sampling makes them
    const double scale = n % 3 == 0 ? 0.1 : 1.0;
    points.emplace_back(scale * where(rng), scale * where(rng), scale * where(rng));
    index.Added();
    if (n % 97 != 0 && n > 40) continue;
    for (const size_t k : {size_t{1}, size_t{7}, size_t{33}, size_t{400}}) {
      const Vec3 q(where(rng), where(rng), where(rng) * (n % 2 == 0 ? 0.1 : 1.0));
      index.KNearest(q, k, &found, &d2);
      std::vector<std::pair<double, size_t>> all;
      for (size_t i = 0; i < points.size(); ++i) all.emplace_back((points[i] - q).squaredNorm(), i);
      std::sort(all.begin(), all.end());
      const size_t expected = std::min(k, points.size());
      REQUIRE(found.size() == expected);
      // the k-th distance matches (ties may swap which equal-distance point is returned)
      const double kth = all[expected - 1].first;
      for (size_t i = 0; i < found.size(); ++i) {
        CHECK(d2[i] == (points[found[i]] - q).squaredNorm());
        CHECK(d2[i] <= kth);
      }
      std::vector<size_t> sorted = found;
      std::sort(sorted.begin(), sorted.end());
      CHECK(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end());  // no duplicates
    }
  }
}

}  // namespace aerobox
