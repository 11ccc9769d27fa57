// Planning every map that has a start and a goal: paths pass a dense second-method re-check.
#include <doctest/doctest.h>

#include <random>

#include "../planning/planning_test_util.h"
#include "common/error.h"
#include "mission/plan.h"
#include "planning/path_simplify.h"
#include "test_support.h"

namespace aerobox {
namespace fs = std::filesystem;
namespace {

void CheckPlan(const std::string& path, bool expect_path) {
  CAPTURE(path);
  const FlightSetup setup = LoadFlightSetup(path, {});
  const PlanOutcome plan = PlanFlight(setup);
  if (!expect_path) {
    CHECK(plan.result.status == PlanStatus::kNoPathWithinBudget);
    CHECK(plan.result.path.empty());
    return;
  }
  REQUIRE(plan.result.status == PlanStatus::kSolved);
  CHECK(plan.result.path.front() == plan.start.used);
  CHECK(plan.result.path.back() == plan.goal.used);
  CHECK(testing::DenselyFree(setup.map, setup.PlannerCollision(), plan.result.path));
  // moved endpoints moved by less than the search radius plus the margin
  CHECK(plan.start.moved < 0.5 + 0.2);
  CHECK(plan.goal.moved < 0.5 + 0.2);

  // the trajectory along the path: solved, within its limits, and free when re-checked densely
  // by the second method (positions at most 1 cm apart, brute force over the map's boxes)
  REQUIRE(plan.trajectory);
  const TrajectoryResult& trajectory = *plan.trajectory;
  REQUIRE(trajectory.status == TrajectoryStatus::kSolved);
  const TrajectoryParams& limits = setup.planning.trajectory;
  const double dt = 0.01 / limits.max_speed;
  std::vector<Vec3> samples;
  for (double t = 0; t < trajectory.trajectory.duration() + dt; t += dt) {
    samples.push_back(trajectory.trajectory.Evaluate(t, kPosition));
    // the scale to the limits is found on 10 ms samples: 0.5 % covers what lies between
    CHECK(trajectory.trajectory.Evaluate(t, kVelocity).norm() <= 1.005 * limits.max_speed);
    CHECK(trajectory.trajectory.Evaluate(t, kAcceleration).norm() <= 1.005 * limits.max_accel);
  }
  CHECK(testing::DenselyFree(setup.map, setup.TrajectoryCollision(), samples));
  CHECK((samples.front() - plan.start.used).norm() < 1e-9);
  CHECK(
      (trajectory.trajectory.Evaluate(trajectory.trajectory.duration(), kPosition) - plan.goal.used)
          .norm() < 1e-9);
}

}  // namespace

TEST_CASE("every shipped scenario plans a collision-free path (impossible: none)") {
  for (const fs::directory_entry& entry : fs::directory_iterator(testing::SourceDir() / "scenes")) {
    if (!entry.is_directory()) continue;
    CheckPlan((entry.path() / "scenario.toml").string(), entry.path().filename() != "impossible");
  }
}

TEST_CASE("every published map with a start and goal plans a collision-free path") {
  AEROBOX_REQUIRE_SHARED_MAPS(maps);
  for (const char* file :
       {"rbe595/map2.txt", "rbe595/p2b_real_map1.txt", "flightsim/test_window.json",
        "flightsim/test_maze.json", "flightsim/test_forest.json", "flightsim/test_over_under.json",
        "flightsim/test_saw.json", "flightsim/test_slide.json", "flightsim/test_empty.json"}) {
    CheckPlan((maps / file).string(), true);
  }
  CheckPlan((maps / "flightsim/test_impossible.json").string(), false);
}

TEST_CASE("endpoints: on the floor or the bounds they move in, inside a box they are errors") {
  Map map;
  map.source = "room.txt";
  map.bounds = {Vec3(0, 0, 0), Vec3(4, 4, 2)};
  map.boxes.push_back({{Vec3(2, 0, 0), Vec3(2.5, 4, 2)}, Vec3(1, 0, 0), "wall", 7});
  const CollisionWorld world(map, CollisionParams());

  const Endpoint floor = ResolveEndpoint(map, world, Vec3(1, 1, 0), "start");
  CHECK(floor.used.isApprox(Vec3(1, 1, 0.125)));  // half the height plus the clearance
  CHECK(floor.moved == doctest::Approx(0.125));
  const Endpoint corner = ResolveEndpoint(map, world, Vec3(0, 4, 1), "goal");
  CHECK(corner.used.isApprox(Vec3(0.15, 3.85, 1)));
  // 5 cm from the wall: moved out of its clearance along a straight free line
  const Endpoint near_wall = ResolveEndpoint(map, world, Vec3(1.9, 1, 1), "start");
  CHECK(world.IsPointFree(near_wall.used));
  CHECK(near_wall.used.x() <= 2 - 0.15 + 1e-9);
  CHECK(near_wall.moved == doctest::Approx(0.05).epsilon(0.2));

  CHECK_THROWS_WITH_AS(ResolveEndpoint(map, world, Vec3(2.2, 1, 1), "start"),
                       "room.txt:7: start: 2.2, 1, 1 lies inside wall (the vehicle does not fit)",
                       InputError);
  CHECK_THROWS_WITH_AS(ResolveEndpoint(map, world, Vec3(1.98, 1, 1), "goal"),
                       doctest::Contains("inside wall"), InputError);
  CHECK_THROWS_WITH_AS(ResolveEndpoint(map, world, Vec3(5, 1, 1), "goal"),
                       "room.txt: goal: 5, 1, 1 lies outside the map bounds", InputError);
}

TEST_CASE("the same seed plans the same path") {
  const std::string scenario = (testing::SourceDir() / "scenes/forest/scenario.toml").string();
  const FlightSetup setup = LoadFlightSetup(scenario, {});
  CHECK(PlanFlight(setup).result.path == PlanFlight(setup).result.path);
}

}  // namespace aerobox

namespace aerobox {

TEST_CASE("the city: the lattice plans 600-700 m queries that pass the dense re-check") {
  AEROBOX_REQUIRE_SHARED_MAPS(maps);
  FlightSetup setup = LoadFlightSetup((maps / "fcnd/colliders.csv").string(), {});
  // seeded random free pairs 600-700 m apart, 10-60 m up
  const CollisionWorld world(setup.map, setup.PlannerCollision());
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> x(setup.map.bounds.min.x() + 5,
                                           setup.map.bounds.max.x() - 5);
  std::uniform_real_distribution<double> y(setup.map.bounds.min.y() + 5,
                                           setup.map.bounds.max.y() - 5);
  std::uniform_real_distribution<double> z(10, 60);
  int queries = 0;
  int solved = 0;
  while (queries < 20) {
    const Vec3 a(x(rng), y(rng), z(rng));
    const Vec3 b(x(rng), y(rng), z(rng));
    const double d = (a - b).head<2>().norm();
    if (d < 600 || d > 700 || !world.IsPointFree(a) || !world.IsPointFree(b)) continue;
    ++queries;
    setup.start = a;
    setup.goal = b;
    const PlanOutcome plan = PlanFlight(setup);
    REQUIRE(plan.lattice);  // a 920 m map: the lattice, not RRT*
    if (plan.result.status != PlanStatus::kSolved) continue;
    ++solved;
    // 5 cm between samples here, not 1 cm: 20 paths of 700 m against 3845 boxes brute force
    // (the exact segment test already passed them; this is the second opinion)
    CHECK(testing::DenselyFree(setup.map, setup.PlannerCollision(), plan.result.path, 0.05));
    CHECK(plan.trajectory);
  }
  MESSAGE("city: " << solved << " of " << queries << " queries solved");
  CHECK(solved == queries);
}

}  // namespace aerobox
