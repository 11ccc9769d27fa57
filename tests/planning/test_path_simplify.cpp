#include <doctest/doctest.h>

#include "planning/path_simplify.h"
#include "planning/planning_test_util.h"

namespace aerobox {

TEST_CASE("pruning and shortcutting shorten a detour and keep it collision-free") {
  Map map;
  map.bounds = {Vec3(0, 0, 0), Vec3(10, 10, 3)};
  map.boxes.push_back({{Vec3(4, 0, 0), Vec3(6, 6, 3)}, Vec3(1, 0, 0), "pillar", 1});
  const CollisionWorld world(map, CollisionParams());
  const Validity validity = testing::ValidityOf(world);
  // a zig-zag around the pillar's free end
  std::vector<Vec3> path = {Vec3(1, 1, 1),   Vec3(1.5, 4, 1.2), Vec3(2, 8, 1), Vec3(5, 9, 2),
                            Vec3(8, 8, 1.5), Vec3(8.5, 4, 1),   Vec3(9, 1, 1)};
  REQUIRE(testing::DenselyFree(map, world.params(), path));
  const double before = PathLength(path);
  PruneWaypoints(validity, &path);
  const double pruned = PathLength(path);
  CHECK(pruned <= before);
  std::mt19937_64 rng(3);
  ShortcutPath(validity, 200, &rng, &path);
  CHECK(PathLength(path) <= pruned);
  CHECK(path.front() == Vec3(1, 1, 1));
  CHECK(path.back() == Vec3(9, 1, 1));
  CHECK(testing::DenselyFree(map, world.params(), path));
  // the shortest way passes the pillar's corner at (4 - 0.15, 6 + 0.15) and (6 + 0.15, 6 + 0.15)
  const double optimum_2d = (Vec3(3.85, 6.15, 0) - Vec3(1, 1, 0)).norm() + 2.3 +
                            (Vec3(9, 1, 0) - Vec3(6.15, 6.15, 0)).norm();
  CHECK(PathLength(path) < 1.05 * optimum_2d);
}

}  // namespace aerobox

namespace aerobox {

TEST_CASE("a polyline's head at an arc length, and the arc length of its point nearest another") {
  const std::vector<Vec3> path = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 3, 0)};
  const std::vector<Vec3> head = PathHead(path, 2.5);
  REQUIRE(head.size() == 3);
  CHECK(head[1].isApprox(Vec3(2, 0, 0)));
  CHECK(head[2].isApprox(Vec3(2, 0.5, 0)));
  CHECK(PathHead(path, 1.0).back().isApprox(Vec3(1, 0, 0)));
  CHECK(PathHead(path, 9.0) == path);
  CHECK(ArcNearest(path, Vec3(1, -1, 0)) == doctest::Approx(1.0));
  CHECK(ArcNearest(path, Vec3(3, 2, 0)) == doctest::Approx(4.0));
  CHECK(ArcNearest(path, Vec3(5, 9, 0)) == doctest::Approx(5.0));
}

}  // namespace aerobox
