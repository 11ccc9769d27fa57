#include <doctest/doctest.h>

#include <random>

#include "geometry/collision_world.h"

namespace aerobox {
namespace {

Map RandomMap(std::uint64_t seed, int boxes) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> where(0.0, 10.0);
  std::uniform_real_distribution<double> size(0.05, 2.0);
  Map map;
  map.bounds = {Vec3(0, 0, 0), Vec3(10, 10, 10)};
  for (int i = 0; i < boxes; ++i) {
    const Vec3 min(where(rng), where(rng), where(rng));
    const Vec3 extent(size(rng), size(rng), size(rng));
    map.boxes.push_back({{min, min + extent}, Vec3(1, 0, 0), "block_" + std::to_string(i), i + 1});
  }
  return map;
}

// The second method: the vehicle's box (grown by the clearance) against every map box, brute
// force, at one point. Touching is allowed, as in CollisionWorld.
bool BruteForceFree(const Map& map, const CollisionParams& params, const Vec3& p) {
  const Vec3 margin = params.Margin();
  const Aabb vehicle{p - margin, p + margin};
  if (!vehicle.IsInside(map.bounds)) return false;
  for (const Box& box : map.boxes) {
    if (box.extent.Overlaps(vehicle)) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("points: free space is outside every box grown by the vehicle and the clearance") {
  Map map;
  map.bounds = {Vec3(0, 0, 0), Vec3(4, 4, 3)};
  map.boxes.push_back({{Vec3(1, 1, 0), Vec3(2, 2, 3)}, Vec3(1, 0, 0), "block_0", 1});
  CollisionParams params;  // 0.10 x 0.10 x 0.05 box, 0.10 clearance: margin 0.15, 0.15, 0.125
  const CollisionWorld world(map, params);
  CHECK(world.free_bounds().min.isApprox(Vec3(0.15, 0.15, 0.125)));
  CHECK(world.IsPointFree(Vec3(0.5, 0.5, 1)));
  CHECK_FALSE(world.IsPointFree(Vec3(0.9, 1.5, 1)));    // 0.1 from the face: inside the margin
  CHECK(world.IsPointFree(Vec3(0.85, 1.5, 1)));         // exactly the margin away: allowed
  CHECK_FALSE(world.IsPointFree(Vec3(0.1, 0.5, 1)));    // too close to the bounds
  CHECK_FALSE(world.IsPointFree(Vec3(0.5, 0.5, 0.1)));  // too close to the floor
  CHECK_FALSE(world.IsPointFree(Vec3(NAN, 0.5, 1)));
  CHECK(world.Clearance(Vec3(0.5, 1.5, 1)) == doctest::Approx(0.45));
  CHECK(world.Clearance(Vec3(0.5, 0.5, 1)) == doctest::Approx(std::sqrt(2 * 0.45 * 0.45)));
  CHECK(world.Clearance(Vec3(1.5, 1.5, 1)) == 0.0);
  CHECK(world.OverlappingBox(Vec3(0.96, 1.5, 1)) == std::optional<size_t>(0));
  CHECK_FALSE(world.OverlappingBox(Vec3(0.95, 1.5, 1)));  // touching only
  const Projection moved = world.ProjectIntoFreeBounds(Vec3(0, 3, 0));
  CHECK(moved.point.isApprox(Vec3(0.15, 3, 0.125)));
  CHECK(moved.moved == doctest::Approx(std::hypot(0.15, 0.125)));
}

TEST_CASE("segments: exact where sampling every 0.5 mm would disagree only by grazing") {
  const Map map = RandomMap(7, 40);
  const CollisionParams params;
  const CollisionWorld world(map, params);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> where(0.2, 9.8);
  int exact_blocked_sampled_free = 0;
  int blocked = 0;
  int tested = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 a(where(rng), where(rng), where(rng));
    Vec3 b = a + Vec3(where(rng) - 5, where(rng) - 5, where(rng) - 5) * 0.3;
    if (!world.IsPointFree(a) || !world.IsPointFree(b)) continue;
    ++tested;
    const bool exact = world.IsSegmentFree(a, b);
    const int samples = static_cast<int>(std::ceil((b - a).norm() / 0.0005)) + 1;
    bool sampled = true;
    for (int s = 0; s <= samples && sampled; ++s) {
      sampled = BruteForceFree(map, params, a + (b - a) * (static_cast<double>(s) / samples));
    }
    // the safety direction never fails: a segment called free has no blocked sample
    if (exact) CHECK(sampled);
    if (!exact) ++blocked;
    if (!exact && sampled) ++exact_blocked_sampled_free;
  }
  CHECK(tested > 1000);
  CHECK(blocked > 100);
  // the other direction fails only for segments that graze an obstacle by less than the sample
  // spacing: a handful in a thousand at most
  CHECK(exact_blocked_sampled_free <= blocked / 200);
}

TEST_CASE("clearance and overlap agree with brute force on a map with many boxes") {
  const Map map = RandomMap(3, 300);
  const CollisionParams params;
  const CollisionWorld world(map, params);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> where(0.0, 10.0);
  const Vec3 half = 0.5 * params.vehicle_size;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p(where(rng), where(rng), where(rng));
    double expected = std::numeric_limits<double>::infinity();
    bool overlaps = false;
    for (const Box& box : map.boxes) {
      const Vec3 gap =
          (box.extent.min - half - p).cwiseMax(p - box.extent.max - half).cwiseMax(0.0);
      expected = std::min(expected, gap.norm());
      overlaps = overlaps || box.extent.Overlaps({p - half, p + half});
    }
    CHECK(world.Clearance(p) == doctest::Approx(expected).epsilon(1e-12));
    CHECK(world.OverlappingBox(p).has_value() == overlaps);
    CHECK(world.IsPointFree(p) == BruteForceFree(map, params, p));
  }
}

TEST_CASE("segments and boxes agree with a test of every box, and a moved world answers the same") {
  // the broad phase (the hierarchy) must not lose a box: the same answers as trying them all
  const Map map = RandomMap(9, 500);
  const CollisionParams params;
  CollisionWorld built(map, params);
  const CollisionWorld world(std::move(built));
  const Vec3 margin = params.Margin();
  // the open interior of a grown box meets the segment (slabs, as the world's own second method)
  const auto enters = [&](const Vec3& a, const Vec3& b, const Aabb& box) {
    double enter = -1e300, exit = 1e300;
    for (int k = 0; k < 3; ++k) {
      const double d = b[k] - a[k];
      if (d == 0.0) {
        if (!(box.min[k] - margin[k] < a[k] && a[k] < box.max[k] + margin[k])) return false;
        continue;
      }
      const double t0 = (box.min[k] - margin[k] - a[k]) / d;
      const double t1 = (box.max[k] + margin[k] - a[k]) / d;
      enter = std::max(enter, std::min(t0, t1));
      exit = std::min(exit, std::max(t0, t1));
    }
    return enter < exit && enter < 1.0 && exit > 0.0;
  };
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> where(0.2, 9.8), step(-1.5, 1.5), side(0.0, 0.8);
  int free_segments = 0, free_boxes = 0, tested = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 a(where(rng), where(rng), where(rng));
    const Vec3 b = (a + Vec3(step(rng), step(rng), step(rng))).cwiseMax(0.2).cwiseMin(9.8);
    if (!world.IsPointFree(a)) continue;
    ++tested;
    bool expected = world.free_bounds().Contains(b);
    for (const Box& box : map.boxes) expected = expected && !enters(a, b, box.extent);
    CHECK(world.IsSegmentFree(a, b) == expected);
    free_segments += expected ? 1 : 0;
    const Aabb query{a, a + Vec3(side(rng), side(rng), side(rng))};
    bool box_free = query.IsInside(world.free_bounds());
    for (const Box& box : map.boxes) {
      box_free =
          box_free && !Aabb{box.extent.min - margin, box.extent.max + margin}.Overlaps(query);
    }
    CHECK(world.IsBoxFree(query) == box_free);
    free_boxes += box_free ? 1 : 0;
  }
  CHECK(tested > 300);
  CHECK(free_segments > 50);
  CHECK(free_segments < tested);
  CHECK(free_boxes > 20);
}

TEST_CASE("a map without boxes and invalid parameters") {
  Map empty;
  empty.bounds = {Vec3(0, 0, 0), Vec3(1, 1, 1)};
  const CollisionWorld world(empty, CollisionParams());
  CHECK(std::isinf(world.Clearance(Vec3(0.5, 0.5, 0.5))));
  CHECK(world.IsSegmentFree(Vec3(0.2, 0.2, 0.2), Vec3(0.8, 0.8, 0.8)));
  CHECK_FALSE(world.IsSegmentFree(Vec3(0.2, 0.2, 0.2), Vec3(0.8, 0.8, 0.95)));  // leaves bounds
  CollisionParams bad;
  bad.clearance = -0.1;
  CHECK_THROWS_AS(CollisionWorld(empty, bad), std::invalid_argument);
}

}  // namespace aerobox
