#include <doctest/doctest.h>

#include <sstream>

#include "common/error.h"
#include "scenario/scenario.h"
#include "test_support.h"

namespace aerobox {
namespace {

using testing::TempDir;

const char* const kMapJson = R"({"bounds": {"extents": [0, 10, 0, 10, 0, 3]},
  "blocks": [{"extents": [4, 6, 4, 6, 0, 3]}],
  "start": [1, 1, 1], "goal": [9, 9, 1]})";

std::string ScenarioError(const std::string& text) {
  std::istringstream in(text);
  try {
    ReadScenario(in, "scenes/x/scenario.toml");
  } catch (const InputError& error) {
    return error.what();
  }
  FAIL_CHECK("no error for: " << text);
  return "";
}

}  // namespace

TEST_CASE("scenario files: keys, defaults and the map path relative to the file") {
  std::istringstream in(
      "# a comment\nname = \"window\"\nmap = \"../maps/w.json\"\nstart = [0.7, -4.3, 0.7]\n"
      "goal = [8, 18, 3]\nseed = 42\n[planner]\n");
  const Scenario scenario = ReadScenario(in, "scenes/window/scenario.toml");
  CHECK(scenario.name == "window");
  CHECK(scenario.map_path == "scenes/maps/w.json");
  CHECK(scenario.start->isApprox(Vec3(0.7, -4.3, 0.7)));
  CHECK(scenario.goal->isApprox(Vec3(8, 18, 3)));
  CHECK(scenario.seed == 42);

  std::istringstream minimal("map = \"m.txt\"\n");
  const Scenario defaults = ReadScenario(minimal, "scenes/forest/scenario.toml");
  CHECK(defaults.name == "forest");  // the folder's name
  CHECK_FALSE(defaults.start);
  CHECK(defaults.seed == 1);
}

TEST_CASE("scenario files: the [planner] table") {
  std::istringstream in(
      "map = \"m.txt\"\n[planner]\nclearance = 0.2\nmax_iterations = 500\ntime_budget = 2.5\n"
      "max_step = 1.5\ngoal_bias = 0.1\nrewire_factor = 1.5\ninformed = false\n"
      "shortcut_attempts = 7\n");
  const Scenario scenario = ReadScenario(in, "s.toml");
  CHECK(scenario.planning.clearance == 0.2);
  const RrtStarParams& rrt = scenario.planning.rrt;
  CHECK(rrt.max_iterations == 500);
  CHECK(rrt.time_budget == 2.5);
  CHECK(rrt.max_step == 1.5);
  CHECK(rrt.goal_bias == 0.1);
  CHECK(rrt.rewire_factor == 1.5);
  CHECK_FALSE(rrt.informed);
  CHECK(rrt.shortcut_attempts == 7);
  // defaults: an iteration budget, so that a seed gives the same path on any machine
  std::istringstream plain("map = \"m.txt\"\n");
  CHECK(ReadScenario(plain, "s.toml").planning.rrt.max_iterations > 0);
}

TEST_CASE("scenario files: the trajectory generator") {
  std::istringstream plain("map = \"m.txt\"\n");
  CHECK(ReadScenario(plain, "s.toml").planning.trajectory_method == "minsnap");
  std::istringstream cubic("map = \"m.txt\"\n[trajectory]\nmethod = \"cubic\"\n");
  CHECK(ReadScenario(cubic, "s.toml").planning.trajectory_method == "cubic");
  CHECK(ScenarioError("map = \"m.txt\"\n[trajectory]\nmethod = \"septic\"\n") ==
        "scenes/x/scenario.toml:3: trajectory.method: expected cubic, given, minsnap, quintic or "
        "septic-full");
}

TEST_CASE("scenario files: errors name the file, the line and the key") {
  CHECK(ScenarioError("map = \"m.txt\"\n[planner]\nclearance = -1\n") ==
        "scenes/x/scenario.toml:3: planner.clearance: expected a number from 0 to 10");
  CHECK(ScenarioError("map = \"m.txt\"\n[planner]\ninformed = 1\n") ==
        "scenes/x/scenario.toml:3: planner.informed: expected true or false");
  CHECK(ScenarioError("name = \"a\"\n") == "scenes/x/scenario.toml:1: map: missing key 'map'");
  CHECK(ScenarioError("map = \"m.txt\"\n\nstart = [1, 2]\n") ==
        "scenes/x/scenario.toml:3: start: expected an array of 3 numbers [x, y, z] in metres");
  CHECK(ScenarioError("map = \"m.txt\"\ngoal = [1, \"2\", 3]\n") ==
        "scenes/x/scenario.toml:2: goal[1]: expected a finite number");
  CHECK(ScenarioError("map = \"m.txt\"\ngoal = [1, nan, 3]\n") ==
        "scenes/x/scenario.toml:2: goal[1]: expected a finite number");
  CHECK(ScenarioError("map = \"m.txt\"\nstrat = [1, 2, 3]\n")
            .rfind("scenes/x/scenario.toml:2: strat: unknown key", 0) == 0);
  CHECK(ScenarioError("map = \"m.txt\"\n[planner]\nrange = 2\n")
            .rfind("scenes/x/scenario.toml:3: planner.range: unknown key", 0) == 0);
  CHECK(ScenarioError("map = \"m.txt\"\n[controller]\ngain = 2\n")
            .rfind("scenes/x/scenario.toml:3: controller.gain: unknown key", 0) == 0);
  CHECK(ScenarioError("map = \"m.txt\"\nseed = -1\n") ==
        "scenes/x/scenario.toml:2: seed: expected a non-negative integer");
  CHECK(ScenarioError("map = \"m.txt\"\nname = \"a/b\"\n")
            .rfind("scenes/x/scenario.toml:2: name:", 0) == 0);
  CHECK(ScenarioError("map = \n").rfind("scenes/x/scenario.toml:1: TOML:", 0) == 0);
}

TEST_CASE("start and goal: command line, then scenario, then map, then the start/goal file") {
  const TempDir dir;
  const std::string map = dir.Write("w.json", kMapJson);
  FlightSetup setup = LoadFlightSetup(map, {});
  CHECK(setup.name == "w");
  CHECK(setup.start.isApprox(Vec3(1, 1, 1)));
  CHECK(setup.start_origin == "map file");

  const std::string scenario =
      dir.Write("s/scenario.toml", "map = \"../w.json\"\nstart = [2, 1, 1]\nseed = 7\n");
  setup = LoadFlightSetup(scenario, {});
  CHECK(setup.name == "s");
  CHECK(setup.start.isApprox(Vec3(2, 1, 1)));
  CHECK(setup.start_origin == "scenario");
  CHECK(setup.goal->isApprox(Vec3(9, 9, 1)));
  CHECK(setup.goal_origin == "map file");
  CHECK(setup.seed == 7);

  SetupOverrides overrides;
  overrides.goal = Vec3(8, 8, 2);
  overrides.seed = 3;
  setup = LoadFlightSetup(scenario, overrides);
  CHECK(setup.goal->isApprox(Vec3(8, 8, 2)));
  CHECK(setup.goal_origin == "command line");
  CHECK(setup.seed == 3);

  // RBE595: the start and goal sit in "<map>.startgoal.txt" beside the map
  const std::string txt = dir.Write("room.txt", "boundary 0 0 0 5 5 2\nblock 2 2 0 3 3 2\n");
  dir.Write("room.startgoal.txt", "start: (0, 0, 0)\ngoal: (4, 4, 1)\n");
  setup = LoadFlightSetup(txt, {});
  CHECK(setup.start.isApprox(Vec3(0, 0, 0)));
  CHECK(setup.start_origin == "start/goal file");
  CHECK(setup.goal->isApprox(Vec3(4, 4, 1)));

  // nothing anywhere: the vehicle rests on the floor at the default start; no goal
  const std::string bare = dir.Write("bare.txt", "boundary 0 0 0 5 5 2\n");
  setup = LoadFlightSetup(bare, {});
  CHECK(setup.start_origin == "default");
  CHECK(setup.start.z() == doctest::Approx(0.025));
  CHECK_FALSE(setup.goal);
}

TEST_CASE("missing or bad files are InputErrors naming them") {
  const TempDir dir;
  CHECK_THROWS_WITH_AS(LoadFlightSetup((dir.path() / "nope.json").string(), {}),
                       doctest::Contains("nope.json: cannot open"), InputError);
  const std::string scenario = dir.Write("s/scenario.toml", "map = \"missing.txt\"\n");
  CHECK_THROWS_WITH_AS(LoadFlightSetup(scenario, {}), doctest::Contains("missing.txt: cannot open"),
                       InputError);
  CHECK_THROWS_WITH_AS(LoadFlightSetup(dir.path().string(), {}), doctest::Contains("is a folder"),
                       InputError);
  const std::string map = dir.Write("bad.txt", "boundary 0 0 0 5 5 2\n");
  dir.Write("bad.startgoal.txt", "start: (0, 0)\ngoal: (4, 4, 1)\n");
  CHECK_THROWS_WITH_AS(LoadFlightSetup(map, {}),
                       doctest::Contains("bad.startgoal.txt:1: start: expected 3 numbers"),
                       InputError);
}

}  // namespace aerobox
