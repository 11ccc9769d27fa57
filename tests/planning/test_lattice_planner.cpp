#include <doctest/doctest.h>

#include <random>

#include "planning/lattice_planner.h"
#include "planning/path_simplify.h"
#include "planning/planning_test_util.h"

namespace aerobox {
namespace {

// A small "city": a 200 x 200 m block of towers on a grid, some tall, some low.
Map Blocks() {
  Map map;
  map.bounds = {Vec3(0, 0, 0), Vec3(200, 200, 60)};
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> height(10, 70);
  int n = 0;
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 8; ++j) {
      const Vec3 min(10 + 24 * i, 10 + 24 * j, 0);
      map.boxes.push_back({{min, min + Vec3(14, 14, std::min(59.0, height(rng)))},
                           Vec3(0.7, 0.7, 0.7),
                           "block_" + std::to_string(n++),
                           n});
    }
  }
  return map;
}

}  // namespace

TEST_CASE("lattice planner: collision-free long paths, built once, queried many times") {
  const Map map = Blocks();
  const CollisionWorld world(map, CollisionParams());
  const Validity validity = testing::ValidityOf(world);
  LatticeParams params;
  params.spacing = 5.0;
  params.vertical_spacing = 5.0;
  params.min_altitude = 5.0;
  params.max_altitude = 55.0;
  const LatticePlanner planner(world.free_bounds(), validity, params);
  CHECK(planner.stats().nodes > 1000);
  CHECK(planner.stats().edges > planner.stats().nodes);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> where(2, 198), up(5, 20);
  int queries = 0;
  while (queries < 20) {
    const Vec3 a(where(rng), where(rng), up(rng));
    const Vec3 b(where(rng), where(rng), up(rng));
    if ((a - b).norm() < 120 || !world.IsPointFree(a) || !world.IsPointFree(b)) continue;
    ++queries;
    CAPTURE(a.transpose());
    CAPTURE(b.transpose());
    const PlanResult result = planner.Plan(a, b);
    REQUIRE(result.status == PlanStatus::kSolved);
    CHECK(result.path.front() == a);
    CHECK(result.path.back() == b);
    CHECK(testing::DenselyFree(map, world.params(), result.path));
    CHECK(result.stats.final_cost <= result.stats.tree_cost + 1e-9);
    CHECK(result.stats.final_cost >= (a - b).norm() - 1e-9);
  }
  CHECK(planner.Plan(Vec3(15, 15, 5), Vec3(100, 100, 10)).status == PlanStatus::kStartInvalid);
}

TEST_CASE("lattice planner: out of a narrow shaft between buildings, where no lattice point is") {
  // four 40 m towers leave a 4 x 4 m shaft, open above, around x = y = 50; the lattice's points
  // are 10 m apart, none inside the shaft
  Map map;
  map.bounds = {Vec3(0, 0, 0), Vec3(100, 100, 60)};
  const auto tower = [&map](const Vec3& min, const Vec3& max) {
    const int n = static_cast<int>(map.boxes.size());
    map.boxes.push_back({{min, max}, Vec3(0.7, 0.7, 0.7), "tower_" + std::to_string(n), n + 1});
  };
  tower(Vec3(33, 33, 0), Vec3(48, 67, 40));  // west
  tower(Vec3(52, 33, 0), Vec3(67, 67, 40));  // east
  tower(Vec3(48, 33, 0), Vec3(52, 48, 40));  // south
  tower(Vec3(48, 52, 0), Vec3(52, 67, 40));  // north
  const CollisionWorld world(map, CollisionParams());
  const Validity validity = testing::ValidityOf(world);
  LatticeParams params;  // 10 m apart, 10-60 m up
  const LatticePlanner planner(world.free_bounds(), validity, params);
  const Vec3 shaft(50, 50, 15);
  const Vec3 away(5, 95, 20);
  REQUIRE(world.IsPointFree(shaft));
  for (const auto& [a, b] : {std::pair(shaft, away), std::pair(away, shaft)}) {
    const PlanResult result = planner.Plan(a, b);
    REQUIRE(result.status == PlanStatus::kSolved);
    CHECK(result.path.front() == a);
    CHECK(result.path.back() == b);
    CHECK(testing::DenselyFree(map, world.params(), result.path));
    // the way out of the shaft leads up through its open top, above the towers
    const Vec3 exit = a == shaft ? result.path[1] : result.path[result.path.size() - 2];
    CHECK((exit - shaft).head<2>().cwiseAbs().maxCoeff() < 2.0);
    CHECK(exit.z() > 40.0);
  }
}

}  // namespace aerobox

namespace aerobox {

TEST_CASE("lattice parameters: the message names the field at fault") {
  LatticeParams params;
  params.vertical_spacing = 0;
  CHECK_THROWS_WITH_AS(params.Validate(), doctest::Contains("LatticeParams.vertical_spacing"),
                       std::invalid_argument);
  params = LatticeParams();
  params.max_altitude = params.min_altitude - 1;
  CHECK_THROWS_WITH_AS(params.Validate(), doctest::Contains("LatticeParams.max_altitude"),
                       std::invalid_argument);
  params = LatticeParams();
  params.shortcut_attempts = -1;
  CHECK_THROWS_WITH_AS(params.Validate(), doctest::Contains("LatticeParams.shortcut_attempts"),
                       std::invalid_argument);
  params = LatticeParams();
  params.spacing = -2;
  CHECK_THROWS_WITH_AS(params.Validate(), doctest::Contains("LatticeParams.spacing"),
                       std::invalid_argument);
}

}  // namespace aerobox
