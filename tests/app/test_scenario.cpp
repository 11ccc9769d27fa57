#include <doctest/doctest.h>

#include <sstream>

#include "common/error.h"
#include "scenario/scenario.h"
#include "test_support.h"

namespace aerobox {
namespace {

using testing::TempDir;

// A setting given on the command line, made field by field (a braced list of them trips GCC 12's
// maybe-uninitialized warning in the sanitizer build).
Setting CommandLine(const std::string& key, const std::string& value, const std::string& option) {
  Setting setting;
  setting.key = key;
  setting.value = value;
  setting.where.file = "command line";
  setting.option = option;
  return setting;
}

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
  CHECK(ScenarioError("map = \"m.txt\"\nsed = 3\n") ==
        "scenes/x/scenario.toml:2: sed: unknown key (expected name, map, start, goal, goals, "
        "stop_at_goals, hold, unknown, unknown_fraction, unknown_map, seed, [[vehicles]], "
        "[planner], [trajectory], [vehicle], [controller], [flight], [wind], [aero], [sensors], "
        "[sensing], [replan], [swarm] or [render]); did you mean seed?");
  CHECK(ScenarioError("map = \"m.txt\"\n[sensor]\nimu = true\n")
            .find("sensor: unknown key (expected name, ") != std::string::npos);
  CHECK(ScenarioError("map = \"m.txt\"\n[sensor]\nimu = true\n").find("did you mean sensors?") !=
        std::string::npos);
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

  // RBE595's own layout: maps/mapN.txt and startandgoal/mapN.txt
  const std::string rbe = dir.Write("rbe/maps/map7.txt", "boundary 0 0 0 5 5 2\n");
  dir.Write("rbe/startandgoal/map7.txt", "start: (1, 1, 1)\ngoal: (4, 3, 1)\n");
  setup = LoadFlightSetup(rbe, {});
  CHECK(setup.start_origin == "start/goal file");
  CHECK(setup.goal->isApprox(Vec3(4, 3, 1)));

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

#include "control/controllers.h"
#include "mission/plan.h"
#include "sim/simulation.h"

namespace aerobox {
namespace {

// A scenario over a 4 x 4 x 2 m room with `tables` appended.
FlightSetup RoomScenario(const TempDir& dir, const std::string& tables) {
  dir.Write("room.txt", "boundary 0 0 0 4 4 2\n");
  return LoadFlightSetup(
      dir.Write("room.toml", "map = \"room.txt\"\nstart = [1, 1, 0]\ngoal = [3, 3, 1]\n" + tables),
      {});
}

}  // namespace

TEST_CASE("[vehicle] reaches the MuJoCo scene") {
  const TempDir dir;
  const FlightSetup setup = RoomScenario(
      dir, "[vehicle]\nmass = 0.1\nmotor_time_constant = 0.03\nmax_rotor_thrust = 0.5\n");
  CHECK(setup.vehicle_kind == "tello");
  const Simulation sim = Simulation::FromXml(SceneMjcfFor(setup), "room");
  const mjModel* m = sim.model();
  const int body = mj_name2id(m, mjOBJ_BODY, "quad");
  CHECK(m->body_mass[body] == doctest::Approx(0.1));
  for (int a = 0; a < m->nu; ++a) {
    CHECK(m->actuator_dynprm[a * mjNDYN] == doctest::Approx(0.03));
    CHECK(m->actuator_ctrlrange[2 * a + 1] == doctest::Approx(0.5));
  }
  // the rotors' arrays
  const FlightSetup wide = RoomScenario(
      dir,
      "[vehicle]\nrotor_positions = [[0.1, 0.1, 0], [0.1, -0.1, 0], [-0.1, -0.1, 0], [-0.1, 0.1, "
      "0]]\nrotor_directions = [-1, 1, -1, 1]\n");
  CHECK(wide.vehicle.rotor_positions_B[1].y() == doctest::Approx(-0.1));
  CHECK(wide.vehicle.rotor_directions[0] == -1);
  const Simulation wide_sim = Simulation::FromXml(SceneMjcfFor(wide), "room");
  CHECK(wide_sim.model()->nu == 4);
  // the Crazyflie's own numbers, by kind
  const FlightSetup cf = RoomScenario(dir, "[vehicle]\nkind = \"crazyflie\"\n");
  const Simulation cf_sim = Simulation::FromXml(SceneMjcfFor(cf), "room");
  CHECK(cf_sim.model()->body_mass[mj_name2id(cf_sim.model(), mjOBJ_BODY, "quad")] ==
        doctest::Approx(0.030));
}

TEST_CASE("[vehicle] reaches the collision worlds and so the planner") {
  const TempDir dir;
  const FlightSetup big = RoomScenario(dir, "[vehicle]\ncollision_size = [0.2, 0.2, 0.1]\n");
  CHECK(big.PlannerCollision().vehicle_size.isApprox(Vec3(0.2, 0.2, 0.1)));
  CHECK(big.TrajectoryCollision().vehicle_size.isApprox(Vec3(0.2, 0.2, 0.1)));
  // a start on the floor moves up by half the vehicle's height plus the clearance
  const PlanOutcome plan = PlanFlight(big);
  CHECK(plan.start.moved == doctest::Approx(0.05 + 0.10));
  const PlanOutcome tello = PlanFlight(RoomScenario(dir, ""));
  CHECK(tello.start.moved == doctest::Approx(0.025 + 0.10));
}

TEST_CASE("[vehicle] and [controller] reach the controller") {
  const TempDir dir;
  const FlightSetup setup =
      RoomScenario(dir, "[vehicle]\nmass = 0.12\n[controller]\nkind = \"se3\"\nrate = 500\n");
  CHECK(setup.controller.kind == "se3");
  CHECK(setup.controller.rate == 500);
  const std::unique_ptr<Controller> controller = MakeController(setup.controller, setup.vehicle);
  State hovering;
  hovering.p_W = Vec3(1, 1, 1);
  FlatOutput setpoint;
  setpoint.p_W = hovering.p_W;
  ControlCommand command;
  REQUIRE(controller->Update(0.0, hovering, setpoint, &command));
  CHECK(command.level == CommandLevel::kThrustMoment);        // SE(3): thrust and moments
  CHECK(command.thrust == doctest::Approx(0.12 * kGravity));  // the scenario's mass holds it up

  const FlightSetup cascade =
      RoomScenario(dir, "[controller]\nposition_gain = 2\nattitude_gain = [6, 6, 3]\n");
  CHECK(cascade.controller.cascade.position_gain.isApprox(Vec3::Constant(2)));
  CHECK(cascade.controller.inner.attitude.gain.isApprox(Vec3(6, 6, 3)));
}

TEST_CASE("[vehicle], [controller] and [flight]: errors name the line and the key") {
  CHECK(ScenarioError("map = \"m.txt\"\n[vehicle]\nkind = \"blimp\"\n") ==
        "scenes/x/scenario.toml:3: vehicle.kind: expected \"tello\" or \"crazyflie\", got "
        "\"blimp\"");
  CHECK(ScenarioError("map = \"m.txt\"\n[vehicle]\nmass = 5\n")
            .rfind("scenes/x/scenario.toml:2: vehicle: QuadParams.max_rotor_thrust 0.4 N cannot "
                   "lift the mass 5 kg",
                   0) == 0);
  // the numbers come from QuadParams' Describe: a misspelt key is named with the one it looks
  // like, a value out of range with the range
  CHECK(ScenarioError("map = \"m.txt\"\n[vehicle]\nmas = 0.1\n")
            .find("vehicle.mas: unknown key (expected kind, mass, inertia, ") != std::string::npos);
  CHECK(ScenarioError("map = \"m.txt\"\n[vehicle]\nmas = 0.1\n")
            .find("moment_coefficient); did you mean mass?") != std::string::npos);
  CHECK(ScenarioError("map = \"m.txt\"\n[vehicle]\ninertia = [1e-5, 1e-5, 20]\n") ==
        "scenes/x/scenario.toml:3: vehicle.inertia[2]: expected a number from 1e-09 to 10");
  CHECK(
      ScenarioError("map = \"m.txt\"\n[vehicle]\nrotor_positions = [[0.1, 0.1, 0]]\n") ==
      "scenes/x/scenario.toml:3: vehicle.rotor_positions: expected 4 points [[x, y, z], ...] in m");
  CHECK(
      ScenarioError("map = \"m.txt\"\n[vehicle]\nrotor_positions = [[0.1, 0.1, 0], [0.1, "
                    "-0.1, 0], [-0.1, -0.1, 0], [-0.1, 0.1, 11]]\n") ==
      "scenes/x/scenario.toml:3: vehicle.rotor_positions[3][2]: expected a number from -10 to 10");
  CHECK(ScenarioError("map = \"m.txt\"\n[vehicle]\nrotor_directions = [1, 1, -1, 2]\n") ==
        "scenes/x/scenario.toml:3: vehicle.rotor_directions[3]: expected 1 or -1 (the sign of the "
        "rotor's yaw moment on the body)");
  CHECK(
      ScenarioError("map = \"m.txt\"\n[vehicle]\nmax_rotor_thrust = 0.5\nrotor_speed_max = 2000\n")
          .find("vehicle.rotor_speed_max: give the rotor limits as thrusts or as speeds") !=
      std::string::npos);
  CHECK(ScenarioError("map = \"m.txt\"\n[controller]\nkind = \"lqr\"\n") ==
        "scenes/x/scenario.toml:3: controller.kind: expected cascade, indi or se3, got \"lqr\"");
  CHECK(ScenarioError("map = \"m.txt\"\n[controller]\nrate = 300\n") ==
        "scenes/x/scenario.toml:3: controller.rate: must divide the 1000 Hz physics rate (e.g. "
        "1000, 500, 250, 200, 100)");
  CHECK(ScenarioError("map = \"m.txt\"\n[controller]\nposition_gain = [1, 2]\n") ==
        "scenes/x/scenario.toml:3: controller.position_gain: expected a number or an array of 3 "
        "numbers");
  CHECK(ScenarioError("map = \"m.txt\"\n[flight]\nyaw = \"spin\"\n") ==
        "scenes/x/scenario.toml:3: flight.yaw: expected \"hold\" or \"travel\"");
  // RotorPy's names: rotor speeds through the thrust coefficient, k_m
  std::istringstream rotorpy(
      "map = \"m.txt\"\n[vehicle]\nthrust_coefficient = 2e-7\nrotor_speed_max = 1500\n"
      "moment_coefficient = 1.2e-9\n");
  const Scenario scenario = ReadScenario(rotorpy, "s.toml");
  CHECK(scenario.vehicle.MaxRotorThrust() == doctest::Approx(2e-7 * 1500 * 1500));
  CHECK(scenario.vehicle.yaw_moment_per_thrust == doctest::Approx(0.006));
}

TEST_CASE("[wind], [aero] and [sensors]: the keys") {
  std::istringstream in(R"(map = "m.txt"
[wind]
mean = [3.0, 0.0, 0.0]
turbulence = "dryden"
intensity = 0.8
[[wind.gusts]]
start = 1.0
peak = 4.0
direction = [0, 1, 0]
[aero]
rotor_drag = false
[sensors]
imu = true
[sensors.position]
kind = "gps"
latency = 0.05
[sensors.estimator]
attitude_sigma = 0.05
)");
  const Scenario s = ReadScenario(in, "scenes/x/scenario.toml");
  CHECK(s.wind.mean == Vec3(3, 0, 0));
  CHECK(s.wind.turbulence == Turbulence::kDryden);
  CHECK(s.wind.intensity == Vec3::Constant(0.8));
  REQUIRE(s.wind.gusts.size() == 1);
  CHECK(s.wind.gusts[0].peak == 4.0);
  CHECK(s.wind.gusts[0].rise == Gust().rise);  // the default
  CHECK_FALSE(s.aero.rotor_drag);
  CHECK_FALSE(s.aero.body_drag);
  CHECK(s.aero_given);
  CHECK(s.sensors.imu.enabled);
  CHECK(s.sensors.position.enabled);
  CHECK(s.sensors.position.kind == PositionSensorKind::kGps);
  CHECK(s.sensors.position.rate == PositionSensorParams::Gps().rate);  // the kind's default
  CHECK(s.sensors.position.latency == 0.05);
  CHECK(s.sensors.estimator.attitude_sigma == 0.05);
}

TEST_CASE("[wind], [aero] and [sensors]: errors name the line and the key") {
  CHECK(ScenarioError("map = \"m.txt\"\n[wind]\nmean = [1, 2]\n") ==
        "scenes/x/scenario.toml:3: wind.mean: expected a number or an array of 3 numbers");
  CHECK(ScenarioError("map = \"m.txt\"\n[wind]\nturbulence = \"karman\"\n") ==
        "scenes/x/scenario.toml:3: wind.turbulence: expected \"dryden\" or \"none\"");
  CHECK(ScenarioError("map = \"m.txt\"\n[wind]\nspeed = 3\n") ==
        "scenes/x/scenario.toml:3: wind.speed: unknown key (expected mean, turbulence, "
        "intensity, min_airspeed or gusts)");
  CHECK(ScenarioError("map = \"m.txt\"\n[wind]\n[[wind.gusts]]\nrise = 2\nduration = 1\n")
            .find("scenes/x/scenario.toml:2: wind: wind.gusts[0].duration: expected at least "
                  "twice the rise") == 0);
  CHECK(ScenarioError("map = \"m.txt\"\n[aero]\ndrag = 1\n") ==
        "scenes/x/scenario.toml:3: aero.drag: expected true or false");
  CHECK(ScenarioError("map = \"m.txt\"\n[sensors]\nimu = true\n") ==
        "scenes/x/scenario.toml:2: sensors: sensors.position: the estimator needs both the IMU "
        "and the position sensor (turn both on, or neither)");
  CHECK(ScenarioError("map = \"m.txt\"\n[sensors]\nimu = true\n[sensors.position]\n"
                      "kind = \"sonar\"\n") ==
        "scenes/x/scenario.toml:5: sensors.position.kind: expected \"mocap\" or \"gps\"");
  CHECK(ScenarioError("map = \"m.txt\"\n[sensors]\nposition = true\n[sensors.imu]\n"
                      "rate = 300\n")
            .find("sensors.imu.rate: 300") != std::string::npos);
  // the wind's, a gust's and the position sensor's keys come from their Describe: a misspelt
  // one is named with the key it looks like, a value out of range with the range
  CHECK(ScenarioError("map = \"m.txt\"\n[wind]\nintensty = 1\n") ==
        "scenes/x/scenario.toml:3: wind.intensty: unknown key (expected mean, turbulence, "
        "intensity, min_airspeed or gusts); did you mean intensity?");
  CHECK(ScenarioError("map = \"m.txt\"\n[wind]\n[[wind.gusts]]\npeak = 60\n") ==
        "scenes/x/scenario.toml:4: wind.gusts[0].peak: expected a number from 0 to 50");
  CHECK(ScenarioError("map = \"m.txt\"\n[sensors]\nimu = true\n[sensors.position]\n"
                      "latncy = 0.1\n") ==
        "scenes/x/scenario.toml:5: sensors.position.latncy: unknown key (expected kind, rate, "
        "noise, latency or attitude_noise); did you mean latency?");
  CHECK(ScenarioError("map = \"m.txt\"\n[sensors]\nimu = true\n[sensors.position]\n"
                      "noise = [0.1, 0.1, 200]\n") ==
        "scenes/x/scenario.toml:5: sensors.position.noise[2]: expected a number from 1e-06 to "
        "100");
  CHECK(ScenarioError("map = \"m.txt\"\n[sensors]\ncamera = true\n") ==
        "scenes/x/scenario.toml:3: sensors.camera: unknown key (expected imu, position or "
        "estimator)");
}

TEST_CASE("wind brings drag and the drag feed-forward unless the scenario says otherwise") {
  const TempDir dir;
  dir.Write("m.json", kMapJson);
  const auto load = [&](const std::string& text) {
    return LoadFlightSetupFromText("map = \"m.json\"\n" + text, (dir.path() / "s.toml").string(),
                                   {});
  };
  const FlightSetup still = load("");
  CHECK_FALSE(still.aero.Enabled());
  CHECK_FALSE(still.controller.drag_feedforward);
  const FlightSetup windy = load("[wind]\nmean = [2, 0, 0]\n");
  CHECK(windy.aero.body_drag);
  CHECK(windy.aero.rotor_drag);
  CHECK(windy.controller.drag_feedforward);
  const FlightSetup no_drag = load("[wind]\nmean = [2, 0, 0]\n[aero]\ndrag = false\n");
  CHECK_FALSE(no_drag.aero.Enabled());
  const FlightSetup no_feedforward =
      load("[aero]\ndrag = true\n[controller]\ndrag_feedforward = false\n");
  CHECK(no_feedforward.aero.Enabled());
  CHECK_FALSE(no_feedforward.controller.drag_feedforward);
  // settings that hold only together (the estimator needs both sensors) are taken together
  SetupOverrides both;
  both.settings = {CommandLine("sensors.imu", "true", ""),
                   CommandLine("sensors.position", "true", "")};
  const FlightSetup sensed =
      LoadFlightSetupFromText("map = \"m.json\"\n", (dir.path() / "s.toml").string(), both);
  CHECK(sensed.sensors.Enabled());
  // the command line's --wind and --turbulence: settings of the [wind] keys
  SetupOverrides overrides;
  overrides.settings = {CommandLine("wind.mean", "[0, 4, 0]", "--wind"),
                        CommandLine("wind.turbulence", "\"dryden\"", "--turbulence"),
                        CommandLine("wind.intensity", "1.5", "--turbulence")};
  const FlightSetup cli =
      LoadFlightSetupFromText("map = \"m.json\"\n", (dir.path() / "s.toml").string(), overrides);
  CHECK(cli.wind.mean == Vec3(0, 4, 0));
  CHECK(cli.wind.turbulence == Turbulence::kDryden);
  CHECK(cli.wind.intensity == Vec3::Constant(1.5));
  CHECK(cli.aero.Enabled());
}

TEST_CASE("goals: a mission's keys, and the command line's goals replace the scenario's") {
  const TempDir dir;
  dir.Write("m.json", kMapJson);
  const std::string file = (dir.path() / "s.toml").string();
  const FlightSetup mission = LoadFlightSetupFromText(
      "map = \"m.json\"\ngoals = [[2, 2, 1], [8, 2, 1], [9, 9, 1]]\nstop_at_goals = true\n"
      "hold = 0.5\n",
      file, {});
  REQUIRE(mission.via.size() == 2);
  CHECK(mission.via[1] == Vec3(8, 2, 1));
  CHECK(*mission.goal == Vec3(9, 9, 1));
  CHECK(mission.stop_at_goals);
  CHECK(mission.hold == 0.5);
  SetupOverrides cli;
  cli.goal = Vec3(9, 8, 1);
  const FlightSetup replaced =
      LoadFlightSetupFromText("map = \"m.json\"\ngoals = [[2, 2, 1], [9, 9, 1]]\n", file, cli);
  CHECK(replaced.via.empty());
  CHECK(*replaced.goal == Vec3(9, 8, 1));
  CHECK(ScenarioError("map = \"m.txt\"\ngoal = [1, 1, 1]\ngoals = [[1, 2, 1]]\n") ==
        "scenes/x/scenario.toml:2: goal: give goal or goals, not both");
  CHECK(ScenarioError("map = \"m.txt\"\ngoals = []\n") ==
        "scenes/x/scenario.toml:2: goals: expected an array of points [[x, y, z], ...] in "
        "metres");
  CHECK(ScenarioError("map = \"m.txt\"\ngoals = [[1, 2, 1], [1, 2]]\n") ==
        "scenes/x/scenario.toml:2: goals[1]: expected an array of 3 numbers [x, y, z] in metres");
  CHECK(ScenarioError("map = \"m.txt\"\nhold = -1\n") ==
        "scenes/x/scenario.toml:2: hold: expected a number from 0 to 600");
}

TEST_CASE("unknown boxes, [sensing] and [replan]: the keys and their errors") {
  const TempDir dir;
  dir.Write("m.json", kMapJson);
  dir.Write("more.txt", "boundary 0 0 0 10 10 3\nblock 7 7 0 8 8 3\n");
  const std::string file = (dir.path() / "s.toml").string();
  const FlightSetup setup = LoadFlightSetupFromText(
      "map = \"m.json\"\nunknown = [0]\nunknown_map = \"more.txt\"\n[sensing]\n"
      "kind = \"camera\"\nrange = 5\nfov = 90\n[replan]\nhorizon = 0.2\n",
      file, {});
  REQUIRE(setup.map.boxes.size() == 2);  // the map's one and the other file's
  CHECK(setup.unknown == std::vector<bool>{true, true});
  CHECK(setup.map.boxes[1].name.rfind("unknown_", 0) == 0);
  CHECK(setup.sensing.kind == SensingParams::Kind::kCamera);
  CHECK(setup.sensing.range == 5.0);
  CHECK(setup.sensing.fov_horizontal == doctest::Approx(M_PI / 2));
  CHECK(setup.replan.horizon == 0.2);
  CHECK_THROWS_WITH_AS(LoadFlightSetupFromText("map = \"m.json\"\nunknown = [4]\n", file, {}),
                       doctest::Contains("s.toml:2: unknown: unknown: box 4 is not in the map"),
                       InputError);
  CHECK(ScenarioError("map = \"m.txt\"\nunknown = [-1]\n") ==
        "scenes/x/scenario.toml:2: unknown[0]: expected a box index (an integer from 0)");
  CHECK(ScenarioError("map = \"m.txt\"\nunknown_fraction = 2\n") ==
        "scenes/x/scenario.toml:2: unknown_fraction: expected a number from 0 to 1");
  CHECK(ScenarioError("map = \"m.txt\"\n[sensing]\nkind = \"lidar\"\n") ==
        "scenes/x/scenario.toml:3: sensing.kind: expected \"omni\", \"camera\" or \"depth\"");
  // a depth camera: its settings, and what a pinhole cannot be
  CHECK(ScenarioError("map = \"m.txt\"\n[sensing]\nkind = \"depth\"\nwidth = 0\n") ==
        "scenes/x/scenario.toml:4: sensing.width: expected a whole number from 1 to 4096");
  CHECK(ScenarioError("map = \"m.txt\"\n[sensing]\nkind = \"depth\"\nfov = 180\n") ==
        "scenes/x/scenario.toml:4: sensing.fov: a depth camera sees less than 180 deg (got 180 "
        "deg)");
  CHECK(ScenarioError("map = \"m.txt\"\n[sensing]\nkind = \"depth\"\nfov_vertical = 180\n")
            .find("scenario.toml:4: sensing.fov_vertical:") != std::string::npos);
  CHECK(ScenarioError("map = \"m.txt\"\n[replan]\nlookahead = 1\n") ==
        "scenes/x/scenario.toml:3: replan.lookahead: unknown key (expected horizon, iterations, "
        "search_iterations, time_budget or max_attempts)");
  // a misspelt key names the key it looks like; a whole number must be whole
  CHECK(ScenarioError("map = \"m.txt\"\n[replan]\ntime_budjet = 1\n") ==
        "scenes/x/scenario.toml:3: replan.time_budjet: unknown key (expected horizon, iterations, "
        "search_iterations, time_budget or max_attempts); did you mean time_budget?");
  CHECK(ScenarioError("map = \"m.txt\"\n[replan]\niterations = 2.5\n") ==
        "scenes/x/scenario.toml:3: replan.iterations: expected a whole number from 0 to 10000000");
  CHECK(ScenarioError("map = \"m.txt\"\n[aero]\nrotor_dreg = true\n") ==
        "scenes/x/scenario.toml:3: aero.rotor_dreg: unknown key (expected drag, body_drag or "
        "rotor_drag); did you mean rotor_drag?");
}

}  // namespace aerobox

namespace aerobox {
namespace {

// A registered controller whose own key has a built-in's name.
struct SameNameGains {
  double position_gain = 1.0;  // [1/s]
  void Describe(Archive& a) {
    a.Number({"position_gain", "1/s", "its own"}, &position_gain, 0, 100);
  }
};

}  // namespace

TEST_CASE("[controller]: a registered kind's own key wins over a built-in field of its name") {
  if (Controllers().Find("test_same_name") == nullptr) {
    Controllers().Register(
        "test_same_name",
        [](const ControllerConfig& config, const QuadParams& vehicle) {
          return Controllers().Find("cascade")->operator()(config, vehicle);
        },
        PluginParameters::Of(SameNameGains()));
  }
  std::istringstream in(
      "map = \"m.txt\"\n[controller]\nposition_gain = 7\n"
      "kind = \"test_same_name\"\nattitude_gain = 3\n");
  const Scenario s = ReadScenario(in, "scenes/x/scenario.toml");
  CHECK(s.controller.params.Get<SameNameGains>().position_gain == 7.0);
  CHECK(s.controller.cascade.position_gain == PositionControlParams().position_gain);
  CHECK(s.controller.inner.attitude.gain == Vec3::Constant(3.0));  // the built-ins' still apply
  CHECK(
      ScenarioError("map = \"m.txt\"\n[controller]\nkind = \"test_same_name\"\nposition_gian = 7\n")
          .find("(expected kind, rate, drag_feedforward, position_gain, ") != std::string::npos);
  CHECK(
      ScenarioError("map = \"m.txt\"\n[controller]\nkind = \"test_same_name\"\nposition_gian = 7\n")
          .find("rate_integral_limit; controller kind \"test_same_name\" adds position_gain); did "
                "you mean position_gain?") != std::string::npos);
}

}  // namespace aerobox

namespace aerobox {
namespace {

// The error a scenario of several vehicles in the swap scene's room gives, read as if it were a
// file beside that room's map.
std::string SwarmError(const std::string& vehicles) {
  const std::string file = (testing::SourceDir() / "scenes" / "swarm_swap" / "x.toml").string();
  try {
    LoadFlightSetupFromText("map = \"map.json\"\n" + vehicles, file, {});
  } catch (const InputError& error) {
    const std::string what = error.what();
    return what.substr(what.find("x.toml"));
  }
  FAIL_CHECK("no error for: " << vehicles);
  return "";
}

}  // namespace

TEST_CASE("[[vehicles]]: each vehicle's own kind, controller and rate, the rest shared") {
  const std::string file = (testing::SourceDir() / "scenes" / "swarm_swap" / "x.toml").string();
  const FlightSetup setup = LoadFlightSetupFromText(
      "map = \"map.json\"\n[controller]\nkind = \"se3\"\n[swarm]\nseparation = 0.2\n"
      "[[vehicles]]\nname = \"a\"\nstart = [1, 0, 1]\ngoal = [-1, 0, 1]\n"
      "[[vehicles]]\nname = \"b\"\nkind = \"crazyflie\"\ncontroller = \"cascade\"\nrate = 500\n"
      "start = [0, 1, 1]\ngoal = [0, -1, 1]\n",
      file, {});
  REQUIRE(setup.vehicles.size() == 2);
  CHECK(setup.vehicles[0].vehicle_kind == "tello");
  CHECK(setup.vehicles[0].controller.kind == "se3");
  CHECK(setup.vehicles[1].vehicle_kind == "crazyflie");
  CHECK(setup.vehicles[1].controller.kind == "cascade");
  CHECK(setup.vehicles[1].controller.rate == 500);
  CHECK(setup.vehicles[1].where.line == 10);
  CHECK(setup.swarm.separation == 0.2);
  // the first vehicle's start and goal stand for the scenario's
  CHECK(setup.start == Vec3(1, 0, 1));
  CHECK(setup.goal == Vec3(-1, 0, 1));
  const FlightSetup b = setup.Member(1);
  CHECK(b.name == "b");
  CHECK(b.vehicle.mass == BuiltinVehicle("crazyflie")->mass);
  CHECK(b.vehicles.empty());
}

TEST_CASE("[[vehicles]]: a vehicle's own values and a mission through goals") {
  const std::string file = (testing::SourceDir() / "scenes" / "swarm_swap" / "x.toml").string();
  const FlightSetup setup = LoadFlightSetupFromText(
      "map = \"map.json\"\n"
      "[[vehicles]]\nname = \"a\"\nstart = [1, 0, 1]\ngoals = [[0, 1, 1], [-1, 0, 1]]\n"
      "[vehicles.vehicle]\nkind = \"crazyflie\"\nmass = 0.04\n"
      "[[vehicles]]\nname = \"b\"\nstart = [0, -1, 1]\ngoal = [0, 1, 1.5]\n",
      file, {});
  REQUIRE(setup.vehicles.size() == 2);
  CHECK(setup.vehicles[0].vehicle_kind == "crazyflie");
  CHECK(setup.vehicles[0].vehicle.mass == 0.04);
  CHECK(setup.vehicles[0].via == std::vector<Vec3>{Vec3(0, 1, 1)});
  CHECK(setup.vehicles[0].goal == Vec3(-1, 0, 1));
  CHECK(setup.Member(0).via.size() == 1);
  CHECK(setup.vehicles[1].vehicle_kind == "tello");
  CHECK(setup.vehicles[1].via.empty());
  CHECK(SwarmError("[[vehicles]]\nname = \"a\"\nstart = [1, 0, 1]\ngoal = [0, 0, 1]\n"
                   "goals = [[0, 1, 1]]\n") ==
        "x.toml:6: vehicles.a.goal: give goal or goals, not both");
  CHECK(SwarmError("[[vehicles]]\nname = \"a\"\nstart = [1, 0, 1]\ngoal = [0, 0, 1]\n"
                   "[vehicles.vehicle]\nmass = -1\n")
            .rfind("x.toml:7: vehicle.mass: expected", 0) == 0);
}

TEST_CASE("[[vehicles]]: bad vehicles are refused naming the vehicle, the file and the line") {
  const std::string a = "[[vehicles]]\nname = \"a\"\nstart = [1, 0, 1]\ngoal = [-1, 0, 1]\n";
  CHECK(SwarmError(a + "[[vehicles]]\nname = \"a\"\nstart = [0, 1, 1]\ngoal = [0, -1, 1]\n") ==
        "x.toml:6: vehicles.name: \"a\" is already the name of the vehicle on line 2");
  CHECK(SwarmError(a + "[[vehicles]]\nname = \"b\"\nstart = [1.05, 0, 1]\ngoal = [0, -1, 1]\n")
            .rfind("x.toml:6: vehicles.b.start: starts 0.05 m from a, inside it", 0) == 0);
  CHECK(SwarmError(a + "[[vehicles]]\nname = \"b\"\nstart = [0, 1, 1]\ngoal = [0, -9, 1]\n")
            .rfind("x.toml:6: vehicles.b.goal: (0, -9, 1) m is outside the map's bounds (-3, -3, "
                   "0) .. (3, 3, 3) m",
                   0) == 0);
  CHECK(SwarmError(a + "[[vehicles]]\nname = \"b\"\nkind = \"blimp\"\nstart = [0, 1, 1]\n"
                       "goal = [0, -1, 1]\n") ==
        "x.toml:6: vehicles.b.kind: expected \"tello\" or \"crazyflie\", got \"blimp\"");
  CHECK(SwarmError("[[vehicles]]\nname = \"a\"\nstart = [1, 0, 1]\n") ==
        "x.toml:2: vehicles.a.goal: missing key: give goal or goals");
  CHECK(SwarmError("[[vehicles]]\nname = \"..\"\nstart = [1, 0, 1]\ngoal = [0, 0, 1]\n")
            .rfind("x.toml:3: vehicles.name: \"..\": expected letters, digits, _ and -", 0) == 0);
  CHECK(SwarmError("start = [1, 1, 1]\n" + a) ==
        "x.toml:2: start: with [[vehicles]], each vehicle's table gives its start and goal");
  CHECK(SwarmError("[[vehicles]]\nname = \"a/b\"\nstart = [1, 0, 1]\ngoal = [0, 0, 1]\n")
            .rfind("x.toml:3: vehicles.name: expected a non-empty string without '/'", 0) == 0);
  CHECK(SwarmError("[[vehicles]]\nnme = \"a\"\n").rfind("x.toml:3: vehicles.nme: unknown key", 0) ==
        0);
}

}  // namespace aerobox

namespace aerobox {

TEST_CASE("se3 in wind integrates its position error unless told, in still air it does not") {
  const std::string file = (testing::SourceDir() / "scenes" / "window" / "x.toml").string();
  const auto load = [&file](const std::string& tables) {
    return LoadFlightSetupFromText("map = \"map.json\"\n[controller]\nkind = \"se3\"\n" + tables,
                                   file, {});
  };
  CHECK(load("").controller.se3.position_integral == Vec3::Zero());
  const FlightSetup windy = load("[wind]\nmean = [3, 0, 0]\n");
  CHECK(windy.controller.se3.position_integral == kSe3WindIntegral);
  CHECK(windy.controller.drag_feedforward);  // the other default that follows the air
  // the disturbance observer meets the force itself; a given integral is kept
  CHECK(load("observer = true\n[wind]\nmean = [3, 0, 0]\n").controller.se3.position_integral ==
        Vec3::Zero());
  CHECK(load("se3_position_integral = 0\n[wind]\nmean = [3, 0, 0]\n")
            .controller.se3.position_integral == Vec3::Zero());
  CHECK(load("se3_position_integral = [4, 4, 6]\n").controller.se3.position_integral ==
        Vec3(4, 4, 6));
}

}  // namespace aerobox
