// Planning every map that has a start and a goal: paths pass a dense second-method re-check.
#include <doctest/doctest.h>

#include <random>

#include "../planning/planning_test_util.h"
#include "common/error.h"
#include "common/number_format.h"
#include "mission/plan.h"
#include "planning/path_simplify.h"
#include "planning/planner.h"
#include "scenario/scenario.h"
#include "test_support.h"
#include "trajectory/feasibility.h"

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
  const TrajectoryParams params = TrajectoryParamsFor(setup);
  REQUIRE(params.objective == TimeObjective::kMinTime);  // the default
  // the vehicle's limits hold everywhere (checked every millisecond here, every 10 ms by the
  // generator: 0.5 % covers what lies between), at every rotor, and the speed stays below the
  // vehicle's top speed
  const FlatnessLimits limits = EffectiveLimits(params);
  const FeasibilityCheck worst = CheckFeasibility(trajectory.trajectory, limits, 0.001);
  CAPTURE(worst.limit);
  CAPTURE(worst.t);
  CHECK(worst.ratio <= 1.005);
  const double dt = 0.01 / limits.max_speed;
  std::vector<Vec3> samples;
  for (double t = 0; t < trajectory.trajectory.duration() + dt; t += dt) {
    samples.push_back(trajectory.trajectory.Evaluate(t, kPosition));
    CHECK(trajectory.trajectory.Evaluate(t, kVelocity).norm() <= 1.005 * limits.max_speed);
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

namespace aerobox {
namespace {

// A 6 x 4.4 x 1 m serpentine: seven walls, each open at one end, leave one 0.45 m wide corridor
// (0.15 m for the vehicle's centre, with its clearance) about 47 m long.
std::string SnakeMap() {
  std::string text = "boundary 0 0 0 6 4.4 1\n";
  double y = 0.45;
  for (int i = 0; i < 7; ++i, y += 0.55) {
    text += (i % 2 == 0 ? "block 0 " : "block 0.45 ") + FormatNumber(y) + " 0 " +
            (i % 2 == 0 ? "5.55 " : "6 ") + FormatNumber(y + 0.1) + " 1\n";
  }
  return text;
}

FlightSetup SnakeSetup(const testing::TempDir& dir, const std::string& planner_table) {
  dir.Write("snake.txt", SnakeMap());
  const std::string scenario = dir.Write("snake.toml",
                                         "map = \"snake.txt\"\nstart = [0.3, 0.2, 0.5]\n"
                                         "goal = [0.3, 4.2, 0.5]\n[planner]\n" +
                                             planner_table);
  return LoadFlightSetup(scenario, {});
}

// A planner of the test's own: straight to the goal when that is free.
class StraightPlanner : public Planner {
 public:
  explicit StraightPlanner(const PlannerContext& context) : context_(context) {}
  PlanResult Plan(const Vec3& start, const Vec3& goal) override {
    PlanResult result;
    if (context_.validity.motion(start, goal)) {
      result.status = PlanStatus::kSolved;
      result.path = {start, goal};
    }
    return result;
  }

 private:
  PlannerContext context_;
};

}  // namespace

TEST_CASE("a small map with long narrow corridors is never reported as having no path") {
  const testing::TempDir dir;
  // RRT* needs about 15,000 samples here: its 4000 iterations count from the first solution
  const PlanOutcome rrt = PlanFlight(SnakeSetup(dir, ""));
  REQUIRE(rrt.result.status == PlanStatus::kSolved);
  CHECK(rrt.planner == "rrt_star");
  CHECK(rrt.result.stats.iterations_to_first_solution > 4000);
  CHECK(testing::DenselyFree(SnakeSetup(dir, "").map, SnakeSetup(dir, "").PlannerCollision(),
                             rrt.result.path));
  CHECK(rrt.result.stats.final_cost > 40);  // along the corridor, not through a wall

  // with a search budget too small for RRT*, the lattice takes over and finds the corridor
  const FlightSetup small = SnakeSetup(dir, "max_search_iterations = 500\n");
  const PlanOutcome fallback = PlanFlight(small);
  REQUIRE(fallback.result.status == PlanStatus::kSolved);
  CHECK(fallback.fallback_spacing > 0);
  CHECK(fallback.fallback_spacing <= 0.15);  // fine enough for the corridor
  CHECK(fallback.planner.find("lattice") == 0);
  CHECK(testing::DenselyFree(small.map, small.PlannerCollision(), fallback.result.path));

  // without the fallback the same budget ends in "no path"
  const PlanOutcome none =
      PlanFlight(SnakeSetup(dir, "max_search_iterations = 500\nlattice_fallback = false\n"));
  CHECK(none.result.status == PlanStatus::kNoPathWithinBudget);
}

TEST_CASE("planners by name: given waypoints are checked, and a user's planner is chosen") {
  const testing::TempDir dir;
  // the corridor's turns as waypoints
  std::string points = "kind = \"waypoints\"\nwaypoints = [";
  for (int i = 0; i < 7; ++i) {
    const double x = i % 2 == 0 ? 5.78 : 0.22;
    const double y0 = 0.225 + 0.55 * i;
    points += "[" + FormatNumber(x) + ", " + FormatNumber(y0) + ", 0.5], [" + FormatNumber(x) +
              ", " + FormatNumber(y0 + 0.55) + ", 0.5]" + (i < 6 ? ", " : "");
  }
  points += "]\n";
  const FlightSetup given = SnakeSetup(dir, points);
  const PlanOutcome followed = PlanFlight(given);
  CAPTURE(points);
  REQUIRE(followed.result.status == PlanStatus::kSolved);
  CHECK(followed.planner == "waypoints");
  CHECK(followed.result.path.size() == 16);
  CHECK(followed.result.path[1].isApprox(given.planning.waypoints[0]));

  // one waypoint inside a wall: the given path is refused with the point named
  const PlanOutcome blocked =
      PlanFlight(SnakeSetup(dir, "kind = \"waypoints\"\nwaypoints = [[3, 0.5, 0.5]]\n"));
  CHECK(blocked.result.status == PlanStatus::kPathBlocked);
  CHECK(blocked.result.stats.blocked_leg == 1);
  CHECK(blocked.result.stats.blocked_point.isApprox(Vec3(3, 0.5, 0.5)));
  CHECK(blocked.blocked_by.find("box 'block_0' (the vehicle would overlap it)") == 0);
  // a leg through a wall: where it first leaves free space, and the box, within its clearance
  const PlanOutcome crossing =
      PlanFlight(SnakeSetup(dir, "kind = \"waypoints\"\nwaypoints = [[0.3, 1.0, 0.5]]\n"));
  REQUIRE(crossing.result.status == PlanStatus::kPathBlocked);
  CHECK(crossing.result.stats.blocked_leg == 1);
  const Vec3 margin = SnakeSetup(dir, "").PlannerCollision().Margin();
  // the vehicle's centre meets the wall (y = 0.45) grown by the vehicle's half size + clearance
  CHECK(crossing.result.stats.blocked_point.isApprox(Vec3(0.3, 0.45 - margin.y(), 0.5), 1e-5));
  CHECK(crossing.blocked_by.find("box 'block_0' (within the ") == 0);
  CHECK(DescribeBlockedPath(crossing).find("the leg to point 1 (0 is the start) leaves free "
                                           "space at (0.3, ") == 0);

  if (Planners().Find("straight") == nullptr) {
    Planners().Register("straight", [](const PlannerConfig&, const PlannerContext& context) {
      return std::make_unique<StraightPlanner>(context);
    });
  }
  const std::string room = dir.Write("room.txt", "boundary 0 0 0 4 4 2\n");
  const std::string scenario = dir.Write("room.toml",
                                         "map = \"room.txt\"\nstart = [1, 1, 1]\ngoal = [3, 3, 1]\n"
                                         "[planner]\nkind = \"straight\"\n");
  const PlanOutcome straight = PlanFlight(LoadFlightSetup(scenario, {}));
  REQUIRE(straight.result.status == PlanStatus::kSolved);
  CHECK(straight.planner == "straight");
  CHECK(straight.result.path.size() == 2);
}

}  // namespace aerobox

namespace aerobox {

TEST_CASE("small maps: every one of 20 seeds gets a trajectory (Ipopt's failures fall back)") {
  const testing::TempDir dir;
  // a lab room with a table and a shelf along one wall (a 1.8 m flight), and a 3 m corridor
  // 0.8 m wide with a pillar in its middle
  dir.Write("lab.txt",
            "boundary 0 0 0 3.5 3 2\nblock 1.2 1.0 0 2.0 1.8 0.8\nblock 0 2.6 0 3.5 3 2\n");
  dir.Write("corridor.txt", "boundary 0 0 0 3 0.8 1.2\nblock 1.4 0.3 0 1.6 0.5 1.2\n");
  const std::pair<const char*, const char*> maps[] = {
      {"lab.txt", "start = [0.5, 0.5, 0.3]\ngoal = [1.6, 2.2, 1.2]\n"},
      {"corridor.txt", "start = [0.2, 0.4, 0.6]\ngoal = [2.8, 0.4, 0.6]\n"}};
  int fallbacks = 0;
  for (const auto& [map, endpoints] : maps) {
    for (int seed = 1; seed <= 20; ++seed) {
      CAPTURE(map);
      CAPTURE(seed);
      const std::string scenario =
          dir.Write("s.toml", "map = \"" + std::string(map) + "\"\n" + endpoints +
                                  "seed = " + std::to_string(seed) + "\n");
      const FlightSetup setup = LoadFlightSetup(scenario, {});
      const PlanOutcome plan = PlanFlight(setup);
      REQUIRE(plan.result.status == PlanStatus::kSolved);
      REQUIRE(plan.trajectory);
      CHECK(plan.trajectory->status == TrajectoryStatus::kSolved);
      fallbacks += plan.trajectory->stats.closed_form_fallback;
    }
  }
  MESSAGE("small maps: " << fallbacks << " of 40 trajectories needed the closed form");
}

}  // namespace aerobox

#include "trajectory/generators.h"

namespace aerobox {
namespace {

// A generator of the test's own: from rest to rest in a straight line, 1 s a metre, ignoring
// the waypoints between (fine in an empty room).
class StraightGenerator : public TrajectoryGenerator {
 public:
  TrajectoryResult Generate(const std::vector<Vec3>& path, const TrajectoryWorld&) override {
    TrajectoryResult result;
    const double duration = std::max(0.1, (path.back() - path.front()).norm());
    result.trajectory = SampledTrajectory({{0.0, path.front(), Vec3::Zero(), Vec3::Zero()},
                                           {duration, path.back(), Vec3::Zero(), Vec3::Zero()}});
    result.waypoints = {path.front(), path.back()};
    result.status = TrajectoryStatus::kSolved;
    result.stats.duration = duration;
    return result;
  }
};

}  // namespace

TEST_CASE("a trajectory generator written outside src/ is chosen by name") {
  if (TrajectoryGenerators().Find("test_straight") == nullptr) {
    TrajectoryGenerators().Register("test_straight", [](const GeneratorConfig&) {
      return std::make_unique<StraightGenerator>();
    });
  }
  const testing::TempDir dir;
  dir.Write("room.txt", "boundary 0 0 0 4 4 2\n");
  const std::string scenario = dir.Write("room.toml",
                                         "map = \"room.txt\"\nstart = [1, 1, 1]\ngoal = [3, 1, 1]\n"
                                         "[trajectory]\nmethod = \"test_straight\"\n");
  const PlanOutcome plan = PlanFlight(LoadFlightSetup(scenario, {}));
  REQUIRE(plan.trajectory);
  REQUIRE(plan.trajectory->status == TrajectoryStatus::kSolved);
  CHECK(plan.trajectory->trajectory.duration() == doctest::Approx(2.0));
  CHECK(plan.trajectory->trajectory.Evaluate3(1.0, kPosition).isApprox(Vec3(2, 1, 1), 1e-9));
}

}  // namespace aerobox
