#include <doctest/doctest.h>

#include <chrono>
#include <thread>

#include "common/stop.h"
#include "planning/path_simplify.h"
#include "planning/planning_test_util.h"
#include "planning/rrt_star.h"

namespace aerobox {
namespace {

// A 10 x 10 x 3 room split by a wall with one window: the straight line is blocked.
Map WindowRoom() {
  Map map;
  map.bounds = {Vec3(0, 0, 0), Vec3(10, 10, 3)};
  map.boxes.push_back({{Vec3(0, 4.8, 0), Vec3(7, 5.2, 3)}, Vec3(1, 0, 0), "wall_left", 1});
  map.boxes.push_back({{Vec3(8, 4.8, 0), Vec3(10, 5.2, 3)}, Vec3(1, 0, 0), "wall_right", 2});
  map.boxes.push_back({{Vec3(7, 4.8, 0), Vec3(8, 5.2, 1)}, Vec3(1, 0, 0), "sill", 3});
  map.boxes.push_back({{Vec3(7, 4.8, 2), Vec3(8, 5.2, 3)}, Vec3(1, 0, 0), "lintel", 4});
  return map;
}

// A 2 x 4 x 1 m room that a wall across it closes: no path from y < 2.4 to y > 2.6.
Map ClosedRoom() {
  Map map;
  map.bounds = {Vec3(0, 0, 0), Vec3(2, 4, 1)};
  map.boxes.push_back({{Vec3(0, 2.4, 0), Vec3(2, 2.6, 1)}, Vec3(1, 0, 0), "wall", 1});
  return map;
}

RrtStarParams Deterministic(long iterations, std::uint64_t seed = 1) {
  RrtStarParams params;
  params.max_iterations = iterations;
  params.time_budget = 60;  // never the limit: the result depends on the seed alone
  params.seed = seed;
  return params;
}

}  // namespace

TEST_CASE("RRT* finds a collision-free path through the window") {
  const Map map = WindowRoom();
  const CollisionWorld world(map, CollisionParams());
  const Vec3 start(2, 1, 1.5);
  const Vec3 goal(2, 9, 1.5);
  const PlanResult result = PlanRrtStar(start, goal, world.free_bounds(),
                                        testing::ValidityOf(world), Deterministic(3000));
  REQUIRE(result.status == PlanStatus::kSolved);
  CHECK(result.path.front() == start);
  CHECK(result.path.back() == goal);
  CHECK(testing::DenselyFree(map, world.params(), result.path));
  // every path crosses y = 5 inside the grown window, x >= 7.15: no path is shorter than the
  // one through its nearest corner, and after shortcutting ours is close to it
  const double lower_bound = 2 * std::hypot(7.15 - 2, 5.0 - 1);
  CHECK(result.stats.final_cost >= lower_bound);
  CHECK(result.stats.final_cost < 1.1 * lower_bound);
  CHECK(result.stats.final_cost <= result.stats.tree_cost + 1e-9);
  CHECK(result.stats.final_cost == doctest::Approx(PathLength(result.path)));
  CHECK(result.stats.time_to_first_solution >= 0);
  CHECK(result.stats.nodes > 10);
  // the iteration budget counts from the first solution: the search for it is never cut short
  REQUIRE(result.stats.iterations_to_first_solution >= 0);
  CHECK(result.stats.iterations - result.stats.iterations_to_first_solution == 3000);
}

TEST_CASE("the same seed gives the same path, another seed another") {
  const Map map = WindowRoom();
  const CollisionWorld world(map, CollisionParams());
  const Validity validity = testing::ValidityOf(world);
  const auto plan = [&](std::uint64_t seed) {
    return PlanRrtStar(Vec3(2, 1, 1.5), Vec3(2, 9, 1.5), world.free_bounds(), validity,
                       Deterministic(2000, seed))
        .path;
  };
  CHECK(plan(4) == plan(4));
  CHECK(plan(4) != plan(5));
}

TEST_CASE("the recorded tree: one edge per node but the root, free, and no change to the path") {
  const Map map = WindowRoom();
  const CollisionWorld world(map, CollisionParams());
  const Validity validity = testing::ValidityOf(world);
  RrtStarParams params = Deterministic(1500);
  const PlanResult plain =
      PlanRrtStar(Vec3(2, 1, 1.5), Vec3(2, 9, 1.5), world.free_bounds(), validity, params);
  CHECK(plain.tree.empty());
  params.record_tree = true;
  const PlanResult recorded =
      PlanRrtStar(Vec3(2, 1, 1.5), Vec3(2, 9, 1.5), world.free_bounds(), validity, params);
  CHECK(recorded.path == plain.path);
  REQUIRE(recorded.tree.size() + 1 == recorded.stats.nodes);
  CHECK(recorded.tree.front().second == Vec3(2, 1, 1.5));  // the first edge leaves the start
  for (const auto& [node, parent] : recorded.tree) CHECK(world.IsSegmentFree(parent, node));
}

TEST_CASE("the best path never gets longer with more iterations") {
  const Map map = WindowRoom();
  const CollisionWorld world(map, CollisionParams());
  const Validity validity = testing::ValidityOf(world);
  double previous = std::numeric_limits<double>::infinity();
  for (const long iterations : {1000L, 2000L, 4000L, 8000L}) {
    const PlanResult result = PlanRrtStar(Vec3(2, 1, 1.5), Vec3(2, 9, 1.5), world.free_bounds(),
                                          validity, Deterministic(iterations));
    REQUIRE(result.status == PlanStatus::kSolved);
    CHECK(result.stats.tree_cost <= previous + 1e-12);
    previous = result.stats.tree_cost;
    // and within one run the anytime curve only goes down
    for (size_t i = 1; i < result.stats.cost_history.size(); ++i) {
      CHECK(result.stats.cost_history[i].second < result.stats.cost_history[i - 1].second);
      CHECK(result.stats.cost_history[i].first >= result.stats.cost_history[i - 1].first);
    }
  }
  // 8000 iterations of informed RRT* come close to the shortest path (through the grown
  // window's corner at x = 7.15, plus a little for the 0.7 m of wall depth it crosses)
  CHECK(previous < 1.10 * 2 * std::hypot(7.15 - 2, 5.0 - 1));
}

TEST_CASE("no path: a wall closes the map, the planner says so within its budget") {
  const Map map = ClosedRoom();
  const CollisionWorld world(map, CollisionParams());
  RrtStarParams params;
  params.time_budget = 0.2;
  const PlanResult result = PlanRrtStar(Vec3(1, 1, 0.5), Vec3(1, 3, 0.5), world.free_bounds(),
                                        testing::ValidityOf(world), params);
  CHECK(result.status == PlanStatus::kNoPathWithinBudget);
  CHECK(result.path.empty());
  CHECK(result.stats.iterations > 100);
  CHECK(result.stats.planning_time < 1.0);  // stopped near its 0.2 s budget
}

TEST_CASE("a stop request (Ctrl-C) ends a minute-long search within milliseconds") {
  const Map map = ClosedRoom();
  const CollisionWorld world(map, CollisionParams());
  RrtStarParams params;
  params.time_budget = 60;
  params.max_search_iterations = 0;  // no limit: only the stop request ends it
  std::thread stopper([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    RequestStop();
  });
  const auto begin = std::chrono::steady_clock::now();
  std::string during;
  try {
    PlanRrtStar(Vec3(1, 1, 0.5), Vec3(1, 3, 0.5), world.free_bounds(), testing::ValidityOf(world),
                params);
  } catch (const Interrupted& stop) {
    during = stop.during();
  }
  const double took =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  stopper.join();
  ClearStopRequest();
  CHECK(during.find("planning the path (RRT*") == 0);
  CHECK(took < 5.0);  // the budget was 60 s: only the request can have ended it
}

TEST_CASE("invalid start or goal are statuses, not exceptions") {
  const Map map = WindowRoom();
  const CollisionWorld world(map, CollisionParams());
  const Validity validity = testing::ValidityOf(world);
  CHECK(PlanRrtStar(Vec3(5, 5, 1.5), Vec3(2, 9, 1.5), world.free_bounds(), validity,
                    Deterministic(10))
            .status == PlanStatus::kStartInvalid);
  CHECK(
      PlanRrtStar(Vec3(2, 1, 1.5), Vec3(2, 9, 5), world.free_bounds(), validity, Deterministic(10))
          .status == PlanStatus::kGoalInvalid);
  RrtStarParams bad;
  bad.goal_bias = 1.0;
  CHECK_THROWS_AS(PlanRrtStar(Vec3(2, 1, 1.5), Vec3(2, 9, 1.5), world.free_bounds(), validity, bad),
                  std::invalid_argument);
}

TEST_CASE("a goal in plain sight is reached in a single straight segment") {
  Map map;
  map.bounds = {Vec3(0, 0, 0), Vec3(5, 5, 3)};
  const CollisionWorld world(map, CollisionParams());
  const PlanResult result = PlanRrtStar(Vec3(1, 1, 1), Vec3(4, 4, 2), world.free_bounds(),
                                        testing::ValidityOf(world), Deterministic(200));
  REQUIRE(result.status == PlanStatus::kSolved);
  CHECK(result.path.size() == 2);
  CHECK(result.stats.time_to_first_solution >= 0);
  CHECK(result.stats.first_cost == doctest::Approx((Vec3(4, 4, 2) - Vec3(1, 1, 1)).norm()));
}

}  // namespace aerobox

namespace aerobox {

TEST_CASE("without a solution RRT* stops at its search budget, deterministically") {
  const Map map = ClosedRoom();
  const CollisionWorld world(map, CollisionParams());
  RrtStarParams params;
  params.max_iterations = 10;
  params.max_search_iterations = 1500;
  params.time_budget = 60;
  const PlanResult result = PlanRrtStar(Vec3(1, 1, 0.5), Vec3(1, 3, 0.5), world.free_bounds(),
                                        testing::ValidityOf(world), params);
  CHECK(result.status == PlanStatus::kNoPathWithinBudget);
  CHECK(result.stats.iterations == 1500);
  CHECK(result.stats.iterations_to_first_solution == -1);
}

}  // namespace aerobox
