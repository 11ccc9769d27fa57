#include <doctest/doctest.h>

#include <algorithm>
#include <map>
#include <sstream>
#include <vector>

#include "app/cli.h"
#include "app/exit_codes.h"
#include "cli_runner.h"
#include "common/error.h"
#include "scenario/scenario.h"
#include "sim/simulation.h"
#include "summary_json.h"
#include "test_support.h"

namespace aerobox {
namespace {

using testing::TempDir;
namespace fs = std::filesystem;

using Run = testing::CliRun;

Run Aerobox(const std::vector<std::string>& args) { return testing::RunAerobox(args); }

const char* const kRoom = "boundary 0 0 0 5 5 2\nblock 2 2 0 3 3 2 0 255 0\n";

}  // namespace

TEST_CASE("--help and --version exit 0 and usage errors exit 2") {
  const Run help = Aerobox({"--help"});
  CHECK(help.code == kExitReachedGoal);
  CHECK(help.out.find("scene") != std::string::npos);
  CHECK(help.out.find("check") != std::string::npos);
  CHECK(Aerobox({"scene", "--help"}).out.find("--output") != std::string::npos);
  const Run version = Aerobox({"--version"});
  CHECK(version.code == kExitReachedGoal);
  CHECK(version.out.find("aerobox " AEROBOX_VERSION " (MuJoCo 2.2.2)") != std::string::npos);
  CHECK(Aerobox({}).code == kExitBadInput);
  CHECK(Aerobox({"fyl"}).code == kExitBadInput);
  CHECK(Aerobox({"check"}).code == kExitBadInput);
}

TEST_CASE("check prints a summary of a good map and exits 0") {
  const TempDir dir;
  const std::string map = dir.Write("room.txt", kRoom + std::string("block 4.5 0 0 5.5 1 1\n"));
  const Run run = Aerobox({"check", map, "--start", "1,1,0", "--goal", "4,4,1"});
  CHECK(run.code == kExitReachedGoal);
  CAPTURE(run.out);
  CAPTURE(run.err);
  CHECK(run.out.find("boxes     2") != std::string::npos);
  CHECK(run.out.find("start     1, 1, 0 (command line)") != std::string::npos);
  CHECK(run.out.find("1 box reaches outside the bounds (kept)") != std::string::npos);
  CHECK(run.out.find("block_1 (line 3)") != std::string::npos);
  CHECK(run.out.find("loads in MuJoCo 2.2.2") != std::string::npos);
  CHECK(run.out.find("result    ok") != std::string::npos);
  // the settings in force
  CHECK(run.out.find("vehicle   tello: 0.08 kg") != std::string::npos);
  CHECK(run.out.find("control   cascade at 250 Hz") != std::string::npos);
  // min-time: the vehicle's limits decide, no cap is set (it read "inf m/s")
  CHECK(run.out.find("no speed cap, no acceleration cap") != std::string::npos);
  CHECK(run.out.find("start moved 0.125 m off the bounds/floor") != std::string::npos);

  // a scenario's tables, resolved
  const std::string scenario =
      dir.Write("cf.toml",
                "map = \"room.txt\"\nstart = [1, 1, 0]\n[vehicle]\nkind = \"crazyflie\"\n"
                "motor_time_constant = 0.03\n[controller]\nkind = \"se3\"\nrate = 500\n");
  const Run cf = Aerobox({"check", scenario});
  CAPTURE(cf.out);
  CHECK(cf.code == kExitReachedGoal);
  CHECK(cf.out.find("vehicle   crazyflie: 0.03 kg") != std::string::npos);
  CHECK(cf.out.find("motor lag 0.03 s") != std::string::npos);
  CHECK(cf.out.find("control   se3 at 500 Hz") != std::string::npos);
  CHECK(cf.out.find("unknown   none: the planner knows every box") != std::string::npos);

  // boxes found in flight: how many, the sensor, the replanning
  const std::string unknown =
      dir.Write("unknown.toml",
                "map = \"room.txt\"\nstart = [1, 1, 0]\ngoal = [4, 4, 1]\nunknown = [0]\n"
                "[sensing]\nkind = \"camera\"\nrange = 2.5\n[replan]\niterations = 200\n");
  const Run u = Aerobox({"check", unknown});
  CAPTURE(u.out);
  CAPTURE(u.err);
  CHECK(u.code == kExitReachedGoal);
  CHECK(u.out.find("unknown   1 of 2 boxes, found in flight by a depth camera along body x") !=
        std::string::npos);
  CHECK(u.out.find("2.5 m at 25 Hz; replanning 0.3 s ahead, RRT* at most 3000 iterations to a "
                   "first solution and 200 after it") != std::string::npos);
  // a depth camera turns the yaw along the travel, unless the scenario chose the yaw
  CHECK(u.out.find("; yaw along the travel") != std::string::npos);
  const std::string held =
      dir.Write("held.toml",
                "map = \"room.txt\"\nstart = [1, 1, 0]\ngoal = [4, 4, 1]\nunknown = [0]\n"
                "[sensing]\nkind = \"camera\"\n[flight]\nyaw = \"hold\"\n");
  const Run h = Aerobox({"check", held});
  CHECK(h.out.find("; yaw held") != std::string::npos);
  const Run flown =
      Aerobox({"fly", held, "--no-video", "--quiet", "--out", (dir.path() / "held").string()});
  CHECK(flown.err.find("warning: the depth camera looks along the body's x axis and the yaw is "
                       "held") != std::string::npos);
}

TEST_CASE("bad maps and points exit 2 with file:line messages") {
  const TempDir dir;
  const std::string bad = dir.Write("bad.txt", "boundary 0 0 0 5 5 2\nblock 1 1 1 2 2\n");
  Run run = Aerobox({"check", bad});
  CHECK(run.code == kExitBadInput);
  CHECK(run.err == "aerobox: error: " + bad +
                       ":2: block: expected 6 numbers (xmin ymin zmin "
                       "xmax ymax zmax) or 9 (with r g b), found 5\n");

  const std::string room = dir.Write("room.txt", kRoom);
  run = Aerobox({"check", room, "--start", "2.5,2.5,1"});
  CHECK(run.code == kExitBadInput);
  CHECK(run.err.find(room + ":2: start (command line): 2.5, 2.5, 1 lies inside block_0") !=
        std::string::npos);
  run = Aerobox({"check", room, "--goal", "9,1,1"});
  CHECK(run.code == kExitBadInput);
  CHECK(run.err.find("goal (command line): 9, 1, 1 lies outside the bounds") != std::string::npos);
  run = Aerobox({"check", room, "--start", "1,1"});
  CHECK(run.code == kExitBadInput);
  CHECK(run.err.find("--start: expected three numbers X,Y,Z") != std::string::npos);
  run = Aerobox({"scene", (dir.path() / "absent.json").string()});
  CHECK(run.code == kExitBadInput);
  CHECK(run.err.find("absent.json: cannot open") != std::string::npos);
}

TEST_CASE("scene and check take a map whose floor is a block, and one with no free spot") {
  const TempDir dir;
  const std::string slabs =
      dir.Write("slabs.txt", "boundary 0 0 0 4 4 3\nblock 0 0 0 4 4 0.2\nblock 0 0 2.8 4 4 3\n");
  const Run check = Aerobox({"check", slabs});
  CAPTURE(check.err);
  CHECK(check.code == kExitReachedGoal);
  CHECK(check.out.find("start     ") != std::string::npos);
  CHECK(check.out.find("0.225 (default)") != std::string::npos);  // on the floor slab
  CHECK(Aerobox({"scene", slabs, "-o", (dir.path() / "slabs.xml").string()}).code ==
        kExitReachedGoal);

  // nowhere free: a scene still, a check that says so, and a plan that refuses
  const std::string full = dir.Write("full.txt", "boundary 0 0 0 2 2 1\nblock 0 0 0 2 2 1\n");
  CHECK(Aerobox({"scene", full, "-o", (dir.path() / "full.xml").string()}).code ==
        kExitReachedGoal);
  const Run none = Aerobox({"check", full});
  CHECK(none.code == kExitReachedGoal);
  CHECK(none.out.find("start     none: no start given") != std::string::npos);
  const Run plan =
      Aerobox({"plan", full, "--goal", "1,1,0.5", "--out", (dir.path() / "out").string()});
  CHECK(plan.code == kExitBadInput);
  CHECK(plan.err.find("no start given and no free spot found") != std::string::npos);
}

TEST_CASE("scene writes a complete file or nothing") {
  const TempDir dir;
  const std::string room = dir.Write("room.txt", kRoom);
  const std::string output = (dir.path() / "room.xml").string();
  const Run run = Aerobox({"scene", room, "-o", output, "--start", "1,1,0"});
  REQUIRE(run.code == kExitReachedGoal);
  const std::string xml = testing::ReadFile(output);
  CHECK(xml.find("<geom name=\"block_0\"") != std::string::npos);
  CHECK_NOTHROW(Simulation::FromFile(output));
  CHECK_FALSE(std::filesystem::exists(output + ".partial"));

  // to standard output without -o
  CHECK(Aerobox({"scene", room, "--start", "1,1,0"}).out == xml);

  const std::string unwritable = (dir.path() / "no" / "such" / "folder" / "x.xml").string();
  const Run failed = Aerobox({"scene", room, "-o", unwritable});
  CHECK(failed.code == kExitBadInput);
  CHECK(failed.err.find("x.xml: cannot write") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir.path() / "no"));

  const std::string bad = dir.Write("bad.txt", "boundary 0 0 0 5 5\n");
  const std::string not_written = (dir.path() / "bad.xml").string();
  CHECK(Aerobox({"scene", bad, "-o", not_written}).code == kExitBadInput);
  CHECK_FALSE(std::filesystem::exists(not_written));
}

TEST_CASE("plan writes path.csv, exits 3 without a path and 2 for unusable endpoints") {
  const TempDir dir;
  const std::string room = dir.Write("room.txt", "boundary 0 0 0 6 6 2\nblock 2.5 0 0 3 4.5 2\n");
  const std::string out = (dir.path() / "out").string();
  const Run run = Aerobox({"plan", room, "--start", "1,1,0", "--goal", "5,1,1", "--out", out});
  CAPTURE(run.err);
  REQUIRE(run.code == kExitReachedGoal);
  CHECK(run.out.find("start moved 0.125 m off the bounds/floor") != std::string::npos);
  CHECK(run.out.find("plan room: solved") != std::string::npos);
  const std::string path = testing::ReadFile(fs::path(out) / "path.csv");
  CHECK(path.rfind("x,y,z\n1,1,0.125\n", 0) == 0);
  CHECK(path.size() > 30);
  // the same seed writes the same bytes; another seed (usually) other ones
  Aerobox({"plan", room, "--start", "1,1,0", "--goal", "5,1,1", "--out", out});
  CHECK(testing::ReadFile(fs::path(out) / "path.csv") == path);

  const std::string closed = dir.Write("closed.json", R"({"bounds": {"extents": [0, 2, 0, 4, 0, 1]},
        "blocks": [{"extents": [0, 2, 2.4, 2.6, 0, 1]}], "start": [1, 1, 0.5], "goal": [1, 3, 0.5]})");
  const Run none = Aerobox({"plan", closed, "--out", (dir.path() / "closed").string()});
  CHECK(none.code == kExitNoPath);
  CHECK(none.out.find("no path within budget") != std::string::npos);
  CHECK_FALSE(fs::exists(dir.path() / "closed" / "path.csv"));

  const Run inside = Aerobox({"plan", room, "--start", "2.7,1,1", "--goal", "5,1,1", "--out", out});
  CHECK(inside.code == kExitBadInput);
  CHECK(inside.err.find(":2: start: 2.7, 1, 1 lies inside block_0") != std::string::npos);

  const std::string blocked = dir.Write("file-not-folder", "");
  const Run unwritable = Aerobox({"plan", room, "--out", blocked + "/sub"});
  CHECK(unwritable.code == kExitBadInput);
  CHECK(unwritable.err.find("cannot create the output folder") != std::string::npos);
}

TEST_CASE("fly checks every option before any work: nothing is planned or written") {
  const TempDir dir;
  const std::string room = dir.Write("room.txt", "boundary 0 0 0 6 6 2\nblock 2.5 0 0 3 4.5 2\n");
  const std::string out = (dir.path() / "out").string();
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--camera", "nosuch"}, "--camera: expected chase, overview or top, got 'nosuch'"},
      {{"--size", "641x480"}, "--size: 641x480: a video needs even sides"},
      {{"--size", "4000x3000"}, "--size: 4000x3000 is outside"},
      {{"--size", "640x480x"}, "--size: expected WxH"},
      {{"--fps", "0"}, "--fps:"},
      {{"--speed", "-1"}, "--speed:"},
      {{"--quality", "ugly"}, "--quality: expected fast or pretty"},
      {{"--wind", "3,0"}, "--wind: expected three numbers X,Y,Z in m/s"},
      // the flags that stand for scenario keys are refused with the keys' own ranges
      {{"--wind", "60,0,0"}, "--wind: wind.mean[0]: expected a number from -50 to 50"},
      {{"--turbulence", "-2"}, "--turbulence: expected a number from 0 to 20"},
      {{"--max-speed", "fast"}, "--max-speed: expected a number from 0.01 to 8"},
      {{"--objective", "fastest"}, "--objective: expected \"min-time\" or \"snap\""}};
  for (const auto& [extra, message] : cases) {
    std::vector<std::string> args = {"fly",   room,      "--start", "1,1,0", "--goal",
                                     "5,1,1", "--quiet", "--out",   out};
    args.insert(args.end(), extra.begin(), extra.end());
    const Run run = Aerobox(args);
    CAPTURE(extra[1]);
    CAPTURE(run.err);
    CHECK(run.code == kExitBadInput);
    CHECK(run.err.find(message) != std::string::npos);
    CHECK(run.out.empty());
    CHECK_FALSE(fs::exists(out));  // not even the output folder
  }
  // an odd size is fine without a video (only PNGs are written)
  const Run odd = Aerobox({"fly", room, "--start", "1,1,0", "--goal", "5,1,1", "--quiet", "--out",
                           out, "--no-video", "--size", "321x241"});
  CHECK(odd.code == kExitReachedGoal);
}

TEST_CASE("fly a given trajectory: aerobox's own trajectory.csv flown as it is") {
  const TempDir dir;
  const std::string room = dir.Write("room.txt", "boundary 0 0 0 6 6 2\nblock 2.5 0 0 3 4.5 2\n");
  const std::string planned = (dir.path() / "planned").string();
  REQUIRE(Aerobox({"plan", room, "--start", "1,1,1", "--goal", "5,1,1", "--out", planned}).code ==
          kExitReachedGoal);
  fs::copy_file(fs::path(planned) / "trajectory.csv", dir.path() / "mine.csv");
  const std::string scenario = dir.Write(
      "given.toml", "map = \"room.txt\"\n[trajectory]\nmethod = \"given\"\nfile = \"mine.csv\"\n");
  const std::string out = (dir.path() / "out").string();
  const Run run = Aerobox({"fly", scenario, "--no-video", "--quiet", "--out", out});
  CAPTURE(run.out);
  CAPTURE(run.err);
  REQUIRE(run.code == kExitReachedGoal);
  // the setpoints are the file's samples (100 Hz in the file, 250 Hz in the telemetry: every
  // 0.04 s both have one)
  std::istringstream file(testing::ReadFile(dir.path() / "mine.csv"));
  std::istringstream telemetry(testing::ReadFile(fs::path(out) / "telemetry.csv"));
  std::string a, b;
  std::getline(file, a);
  std::getline(telemetry, b);
  int compared = 0;
  for (int row = 0; std::getline(file, a); ++row) {
    if (row % 4 != 0) continue;
    std::string t_row;
    for (int skip = 0; skip < (row == 0 ? 1 : 10) && std::getline(telemetry, t_row); ++skip) {
    }
    std::vector<double> x, y;
    std::istringstream fa(a), fb(t_row);
    for (std::string cell; std::getline(fa, cell, ',');) x.push_back(std::stod(cell));
    for (std::string cell; std::getline(fb, cell, ',');) y.push_back(std::stod(cell));
    REQUIRE(y.size() > 17);
    CHECK(y[0] == doctest::Approx(x[0]).epsilon(1e-9));
    for (int k = 0; k < 3; ++k) CHECK(y[14 + k] == doctest::Approx(x[1 + k]).epsilon(1e-9));
    ++compared;
  }
  CHECK(compared > 20);
  // a file that is not a trajectory names its line
  dir.Write("bad.csv", "t,x,y,z,vx,vy,vz,ax,ay,az\n0,1,1,1,0,0,0,0,0,0\n0.1,1,1\n");
  const std::string bad = dir.Write(
      "bad.toml", "map = \"room.txt\"\n[trajectory]\nmethod = \"given\"\nfile = \"bad.csv\"\n");
  const Run refused = Aerobox({"fly", bad, "--no-video", "--quiet", "--out", out + "2"});
  CHECK(refused.code == kExitBadInput);
  CHECK(refused.err.find("bad.csv:3: sample:") != std::string::npos);
}

TEST_CASE(
    "a flight from the floor: the take-off on its own, tracking from the trajectory's start") {
  const TempDir dir;
  const std::string room = dir.Write("room.txt", kRoom);
  const std::string out = (dir.path() / "out").string();
  // the start on the floor: the trajectory starts 0.1 m above where the vehicle rests
  const Run run = Aerobox(
      {"fly", room, "--start", "1,1,0", "--goal", "4,4,1", "--no-video", "--quiet", "--out", out});
  CAPTURE(run.out);
  REQUIRE(run.code == kExitReachedGoal);
  CHECK(run.out.find("s of it lifting off the floor") != std::string::npos);
  const nlohmann::json summary = testing::ReadSummary(fs::path(out) / "summary.json");
  CHECK(summary["takeoff_s"].get<double>() > 0.1);
  CHECK(summary["takeoff_s"].get<double>() < 3.0);
  // before, the 0.1 m from the floor to the start was counted as a tracking error
  CHECK(summary["tracking_max_m"].get<double>() < 0.05);
}

TEST_CASE(
    "a blocked given path: exit 3, the leg, the point and the box, in the table and the summary") {
  const TempDir dir;
  dir.Write("room.txt", kRoom);
  const std::string scenario =
      dir.Write("blocked.toml",
                "map = \"room.txt\"\nstart = [1, 1, 1]\ngoal = [4, 4, 1]\n[planner]\n"
                "kind = \"waypoints\"\nwaypoints = [[1, 4, 1], [2.5, 4, 1], [2.5, 1, 1]]\n");
  const std::string out = (dir.path() / "out").string();
  const Run run = Aerobox({"fly", scenario, "--no-video", "--quiet", "--out", out});
  CHECK(run.code == kExitNoPath);
  CAPTURE(run.out);
  // the third leg, from (2.5, 4, 1) down to (2.5, 1, 1), enters block_0 (y 2..3) from above
  CHECK(run.out.find("the leg to point 3 (0 is the start) leaves free space at (2.5, 3.") !=
        std::string::npos);
  CHECK(run.out.find("box 'block_0' (within the ") != std::string::npos);
  const nlohmann::json summary = testing::ReadSummary(fs::path(out) / "summary.json");
  CHECK(summary["status"] == "no path");
  CHECK(summary["blocked_leg"] == 3);
  CHECK(summary["blocked_by"].get<std::string>().find("box 'block_0'") == 0);
  CHECK(summary["blocked_point"][0] == doctest::Approx(2.5));
  CHECK(summary["blocked_point"][1] > 3.0);
}

TEST_CASE("fly: --max-speed, --max-accel, --telemetry-rate, --playback, scenarios named by stem") {
  const TempDir dir;
  dir.Write("room.txt", "boundary 0 0 0 6 6 2\nblock 2.5 0 0 3 4.5 2\n");
  // two scenarios in one folder: each is named after its file, so each has its own outputs
  const std::string slow =
      dir.Write("slow.toml", "map = \"room.txt\"\nstart = [1, 1, 1]\ngoal = [5, 1, 1]\n");
  CHECK(LoadFlightSetup(slow, {}).name == "slow");
  const std::string out = (dir.path() / "out").string();
  const Run run = Aerobox({"fly", slow, "--no-video", "--quiet", "--out", out, "--max-speed", "1",
                           "--max-accel", "1.5", "--telemetry-rate", "50", "--playback", "2"});
  CAPTURE(run.err);
  REQUIRE(run.code == kExitReachedGoal);
  const nlohmann::json summary = testing::ReadSummary(fs::path(out) / "summary.json");
  CHECK(summary["speed_limit_mps"] == 1.0);
  CHECK(summary["accel_limit_mps2"] == 1.5);
  // the scale to the limit is found on 10 ms samples: 0.5 % covers what lies between
  CHECK(testing::SummaryNumber(summary, "trajectory_max_speed_mps") <= 1.005);
  CHECK(summary["telemetry_rate_hz"] == 50.0);
  const std::string telemetry = testing::ReadFile(fs::path(out) / "telemetry.csv");
  const double rows = static_cast<double>(std::count(telemetry.begin(), telemetry.end(), '\n') - 1);
  CHECK(rows ==
        doctest::Approx(50 * testing::SummaryNumber(summary, "flight_time_s")).epsilon(0.02));
  CHECK(Aerobox({"fly", slow, "--no-video", "--quiet", "--out", out, "--telemetry-rate", "300"})
            .err.find("--telemetry-rate: must divide the controller's rate, 250 Hz") !=
        std::string::npos);
  CHECK(Aerobox({"fly", slow, "--no-video", "--quiet", "--out", out, "--max-speed", "20"})
            .err.find("--max-speed: expected a number from 0.01 to 8") != std::string::npos);
  // 0 is a value like any other, not "unset": refused as a scenario refuses it
  const Run zero =
      Aerobox({"fly", slow, "--no-video", "--quiet", "--out", out, "--max-speed", "0"});
  CHECK(zero.code == 2);
  CHECK(zero.err.find("--max-speed: expected a number from 0.01 to 8") != std::string::npos);
  CHECK(Aerobox({"plan", slow, "--out", out, "--max-accel", "0"}).code == 2);
  // a Crazyflie's own top speed bounds it, not the Tello's
  CHECK(Aerobox({"plan", slow, "--out", out, "--set", "vehicle.kind=\"crazyflie\"", "--max-speed",
                 "7.5"})
            .err.find("--max-speed: expected 0.01 to ") != std::string::npos);
}

TEST_CASE("fly --wind --turbulence: the wind, its drag and their columns") {
  const TempDir dir;
  const std::string room = dir.Write("room.txt", "boundary 0 0 0 6 6 2\nblock 2.5 0 0 3 4.5 2\n");
  const std::string out = (dir.path() / "out").string();
  const Run run = Aerobox({"fly", room, "--start", "1,1,1", "--goal", "5,1,1", "--quiet",
                           "--no-video", "--out", out, "--wind", "1.5,0,0", "--turbulence", "0.3"});
  CAPTURE(run.err);
  REQUIRE(run.code == kExitReachedGoal);
  const nlohmann::json summary = testing::ReadSummary(fs::path(out) / "summary.json");
  CHECK(summary["wind"]["mean_mps"][0] == 1.5);
  CHECK(summary["wind"]["turbulence"] == "dryden");
  CHECK(summary["aero"]["body_drag"] == true);
  CHECK(summary["sensors"]["imu"] == false);
  CHECK(testing::SummaryNumber(summary, "max_wind_mps") > 1.0);
  const std::string telemetry = testing::ReadFile(fs::path(out) / "telemetry.csv");
  const std::string header = telemetry.substr(0, telemetry.find('\n'));
  CHECK(header.find(",wind_x,wind_y,wind_z,drag_x,drag_y,drag_z") != std::string::npos);
  CHECK(header.find("est_x") == std::string::npos);  // no sensors: no estimate columns
  // still air: the ideal flight's columns only
  const Run still = Aerobox(
      {"fly", room, "--start", "1,1,1", "--goal", "5,1,1", "--quiet", "--no-video", "--out", out});
  REQUIRE(still.code == kExitReachedGoal);
  const std::string ideal = testing::ReadFile(fs::path(out) / "telemetry.csv");
  CHECK(ideal.substr(0, ideal.find('\n')).find("wind_x") == std::string::npos);
}

namespace {

// telemetry.csv as columns by name.
std::map<std::string, std::vector<double>> ReadColumns(const fs::path& file) {
  std::istringstream text(testing::ReadFile(file));
  std::string line;
  std::getline(text, line);
  std::vector<std::string> names;
  std::istringstream header(line);
  for (std::string name; std::getline(header, name, ',');) names.push_back(name);
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(text, line)) {
    std::istringstream fields(line);
    std::string field;
    for (size_t i = 0; i < names.size() && std::getline(fields, field, ','); ++i) {
      columns[names[i]].push_back(std::stod(field));
    }
  }
  return columns;
}

}  // namespace

TEST_CASE("a mission flies through its goals in order, or stops at each when asked") {
  const TempDir dir;
  const fs::path maze = testing::SourceDir() / "scenes" / "maze" / "map.json";
  const std::string goals = "goals = [[1.5, 3.0, 1.5], [5.0, 4.0, 1.5], [9.0, 7.0, 1.5]]\n";
  const std::string through = dir.Write(
      "through.toml", "map = \"" + maze.string() + "\"\nstart = [1.0, 5.0, 1.5]\n" + goals);
  const std::string stopping =
      dir.Write("stopping.toml", "map = \"" + maze.string() +
                                     "\"\nstart = [1.0, 5.0, 1.5]\nstop_at_goals = true\n"
                                     "hold = 1.0\n" +
                                     goals);
  for (const std::string& scenario : {through, stopping}) {
    CAPTURE(scenario);
    const bool stops = scenario == stopping;
    const fs::path out = dir.path() / (stops ? "stop" : "through");
    const Run run = Aerobox({"fly", scenario, "--no-video", "--quiet", "--out", out.string()});
    CAPTURE(run.err);
    REQUIRE(run.code == kExitReachedGoal);
    const nlohmann::json summary = testing::ReadSummary(out / "summary.json");
    REQUIRE(summary["goals"].size() == 3);
    auto columns = ReadColumns(out / "telemetry.csv");
    const std::vector<double>& t = columns["t"];
    const std::vector<double>& index = columns["goal_index"];
    REQUIRE(index.size() == t.size());
    CHECK(index.front() == 0);
    CHECK(index.back() == 2);  // the last goal ends the flight
    double slowest = 1e9;      // between the first second and the last
    double still_at_goal = 0;  // [s] below 0.1 m/s within 0.1 m of goal 1
    const Vec3 first(1.5, 3.0, 1.5);
    for (size_t i = 0; i < t.size(); ++i) {
      CHECK(index[i] >= (i > 0 ? index[i - 1] : 0));  // goals are reached in order
      const Vec3 v(columns["vx"][i], columns["vy"][i], columns["vz"][i]);
      const Vec3 p(columns["x"][i], columns["y"][i], columns["z"][i]);
      if (t[i] > 1.0 && t[i] < t.back() - 1.0) slowest = std::min(slowest, v.norm());
      if ((p - first).norm() < 0.1 && v.norm() < 0.1) still_at_goal += t[1] - t[0];
    }
    if (stops) {
      CHECK(still_at_goal >= 1.0);  // the hold
    } else {
      CHECK(slowest > 0.5);  // it flies through
      CHECK(still_at_goal == 0.0);
    }
  }
  // the same mission from the command line: --goal several times
  const fs::path out = dir.path() / "cli";
  const Run run = Aerobox({"fly", maze.string(), "--start", "1,5,1.5", "--goal", "1.5,3,1.5",
                           "--goal", "9,7,1.5", "--no-video", "--quiet", "--out", out.string()});
  CAPTURE(run.err);
  REQUIRE(run.code == kExitReachedGoal);
  CHECK(run.out.find("goals       2 of 2 reached") != std::string::npos);
  // a goal inside a wall names it
  const Run bad = Aerobox({"fly", maze.string(), "--start", "1,5,1.5", "--goal", "5.05,5.5,1.5",
                           "--goal", "9,7,1.5", "--no-video", "--quiet", "--out", out.string()});
  CHECK(bad.code == kExitBadInput);
  CHECK(bad.err.find("goals[0]") != std::string::npos);
}

TEST_CASE("model writes the vehicle's MJCF") {
  const Run run = Aerobox({"model"});
  CHECK(run.code == kExitReachedGoal);
  CHECK(run.out.find("<body name=\"quad\"") != std::string::npos);
}

}  // namespace aerobox

namespace aerobox {

TEST_CASE("fly: plans, flies and writes path, trajectory, telemetry and summary") {
  const testing::TempDir dir;
  const std::string room = dir.Write("room.txt", "boundary 0 0 0 6 6 2\nblock 2.5 0 0 3 4.5 2\n");
  const std::string out = (dir.path() / "out").string();
  std::vector<const char*> argv = {"aerobox", "fly",   room.c_str(), "--start",   "1,1,0",
                                   "--goal",  "5,1,1", "--out",      out.c_str(), "--no-video"};
  std::ostringstream stdout_text, stderr_text;
  const int code = RunCli(static_cast<int>(argv.size()), argv.data(), stdout_text, stderr_text);
  CAPTURE(stdout_text.str());
  CAPTURE(stderr_text.str());
  REQUIRE(code == kExitReachedGoal);
  CHECK(stdout_text.str().find("flight      reached goal") != std::string::npos);
  for (const char* name : {"path.csv", "trajectory.csv", "telemetry.csv", "summary.json"}) {
    CAPTURE(name);
    CHECK(std::filesystem::exists(std::filesystem::path(out) / name));
  }
  const std::string telemetry = testing::ReadFile(std::filesystem::path(out) / "telemetry.csv");
  // the contract's columns, in order, then ours
  CHECK(telemetry.rfind("t,x,y,z,vx,vy,vz,qw,qx,qy,qz,wx,wy,wz,x_des,y_des,z_des,vx_des,vy_des,"
                        "vz_des,ax_des,ay_des,az_des,f1,f2,f3,f4,pos_err,",
                        0) == 0);
  CHECK(std::count(telemetry.begin(), telemetry.end(), '\n') > 100);
  const nlohmann::json summary = testing::ReadSummary(std::filesystem::path(out) / "summary.json");
  CHECK(summary["status"] == "reached goal");
  CHECK(testing::SummaryNumber(summary, "tracking_rms_m") < 0.06);
  CHECK(testing::SummaryNumber(summary, "min_clearance_m") > 0);
  CHECK(summary["seed"] == 1);
  // the start on the floor moved up: said, and both points in the summary
  CHECK(
      stdout_text.str().find("start moved 0.125 m off the bounds/floor: 1, 1, 0 -> 1, 1, 0.125") !=
      std::string::npos);
  CHECK(summary["start_requested"] == nlohmann::json::array({1, 1, 0}));
  CHECK(summary["start"][2].get<double>() == doctest::Approx(0.125));
  CHECK(summary["goal_requested"] == summary["goal"]);
  CHECK(summary["map"] == room);
  // min-time: below the Tello's top speed, no acceleration cap
  CHECK(summary["speed_limit_mps"] == 8.0);
  CHECK(summary["accel_limit_mps2"].is_null());
  CHECK(summary["trajectory_objective"] == "min-time");
  // how fast and how hard it flew: the speed stays near the trajectory's (it tracks within
  // centimetres), a hover takes about half of a Tello's thrust, nothing saturates: the
  // trajectory leaves the rotors a margin
  const double top = testing::SummaryNumber(summary, "top_speed_mps");
  CHECK(top ==
        doctest::Approx(testing::SummaryNumber(summary, "trajectory_max_speed_mps")).epsilon(0.05));
  CHECK(testing::SummaryNumber(summary, "average_speed_mps") ==
        doctest::Approx(testing::SummaryNumber(summary, "distance_flown_m") /
                        testing::SummaryNumber(summary, "flight_time_s")));
  CHECK(testing::SummaryNumber(summary, "average_speed_mps") < top);
  const double peak = testing::SummaryNumber(summary, "peak_rotor_command_fraction");
  CHECK(peak > 0.45);
  CHECK(peak < 1.0);
  CHECK(testing::SummaryNumber(summary, "rotor_saturated_s") == 0.0);

  // the same seed gives byte-identical path, trajectory and telemetry
  const std::string again = (dir.path() / "again").string();
  argv[8] = again.c_str();
  std::ostringstream ignored;
  REQUIRE(RunCli(static_cast<int>(argv.size()), argv.data(), ignored, ignored) == kExitReachedGoal);
  for (const char* name : {"path.csv", "trajectory.csv", "telemetry.csv"}) {
    CAPTURE(name);
    CHECK(testing::ReadFile(std::filesystem::path(out) / name) ==
          testing::ReadFile(std::filesystem::path(again) / name));
  }
}

}  // namespace aerobox

#include "outputs/files.h"

namespace aerobox {

TEST_CASE("a streamed file appears only when committed") {
  const testing::TempDir dir;
  const std::string path = (dir.path() / "telemetry.csv").string();
  {
    StreamingFile file(path);
    file.Append("t,x\n");
    file.Append("0,1\n");
    CHECK_FALSE(std::filesystem::exists(path));
    file.Commit();
  }
  CHECK(testing::ReadFile(path) == "t,x\n0,1\n");
  const std::string cut = (dir.path() / "cut.csv").string();
  {
    StreamingFile file(cut);
    file.Append("t,x\n");
  }  // a failure or Ctrl-C: no commit
  CHECK_FALSE(std::filesystem::exists(cut));
  CHECK_FALSE(std::filesystem::exists(cut + ".partial"));
  CHECK_THROWS_AS(StreamingFile((dir.path() / "no" / "dir.csv").string()), InputError);
}

}  // namespace aerobox

namespace aerobox {

TEST_CASE("fly --show-tree: 3 s of the tree growing open the video, and --trajectory is checked") {
  const std::string scenario = (testing::SourceDir() / "scenes/window/scenario.toml").string();
  const TempDir dir;
  const auto frames = [&](const std::vector<std::string>& extra, const std::string& name) {
    std::vector<std::string> args = {
        "fly", scenario, "--size", "160x120", "--quiet", "--out", (dir.path() / name).string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const Run run = Aerobox(args);
    REQUIRE(run.code == kExitReachedGoal);
    return testing::ReadSummary(dir.path() / name / "summary.json")["video_frames"].get<int>();
  };
  CHECK(frames({"--show-tree"}, "tree") == frames({}, "plain") + 90);  // 3 s at 30 fps
  const Run bad = Aerobox({"fly", scenario, "--no-video", "--trajectory", "septic"});
  CHECK(bad.code == kExitBadInput);
  CHECK(bad.err.find("--trajectory: expected cubic, given, minsnap, quintic or septic-full") !=
        std::string::npos);
}

}  // namespace aerobox

namespace aerobox {

TEST_CASE("limits the vehicle cannot follow are said before the flight and in the verdict") {
  const std::string maze = (testing::SourceDir() / "scenes/maze/scenario.toml").string();
  const testing::TempDir dir;
  const testing::CliRun run = testing::RunAerobox(
      {"fly", maze, "--no-video", "--quiet", "--out", (dir.path() / "out").string(), "--objective",
       "snap", "--max-speed", "8", "--max-accel", "10"});
  CAPTURE(run.out);
  // a Tello tilts at most 0.6 rad: g tan(0.6) = 6.7 m/s^2 horizontally
  CHECK(run.err.find("aerobox: warning: the trajectory may accelerate at 10 m/s^2, but this "
                     "vehicle reaches about 6.7 m/s^2") != std::string::npos);
  const nlohmann::json summary = testing::ReadSummary(dir.path() / "out" / "summary.json");
  CHECK(summary["tracking_warning"].get<std::string>().find("off its trajectory") !=
        std::string::npos);
  CHECK(run.out.find("  warning     the vehicle was up to") != std::string::npos);

  // min-time (the default) flies within the vehicle's own limits: a cap above them says nothing,
  // and the flight follows its trajectory
  const testing::CliRun fast =
      testing::RunAerobox({"fly", maze, "--no-video", "--quiet", "--out",
                           (dir.path() / "fast").string(), "--max-accel", "10"});
  CAPTURE(fast.out);
  CHECK(fast.code == 0);
  CHECK(fast.err.find("warning") == std::string::npos);
  const nlohmann::json fast_summary = testing::ReadSummary(dir.path() / "fast" / "summary.json");
  CHECK(fast_summary["tracking_warning"].get<std::string>().empty());
  CHECK(fast_summary["trajectory_objective"] == "min-time");
  CHECK(fast_summary["trajectory_binding_ratio"].get<double>() <= 1.0);

  // --objective snap alone: the snap objective's own 2 m/s and 2 m/s^2
  const testing::CliRun snap =
      testing::RunAerobox({"fly", maze, "--no-video", "--quiet", "--out",
                           (dir.path() / "snap").string(), "--objective", "snap"});
  CHECK(snap.code == 0);
  const nlohmann::json snap_summary = testing::ReadSummary(dir.path() / "snap" / "summary.json");
  CHECK(snap_summary["speed_limit_mps"] == 2.0);
  CHECK(snap_summary["accel_limit_mps2"] == 2.0);
  CHECK(snap_summary["trajectory_max_speed_mps"].get<double>() <= 2.0 * 1.005);
  CHECK(Aerobox({"fly", maze, "--objective", "fastest"}).code == kExitBadInput);
}

}  // namespace aerobox

namespace aerobox {

TEST_CASE("--set works on a bare map, and the flags are --set in other words") {
  const TempDir dir;
  const std::string room = dir.Write("room.txt", "boundary 0 0 0 6 6 2\n");
  const auto plan = [&](const std::string& name, std::vector<std::string> extra) {
    std::vector<std::string> args = {"plan",   room,    "--start", "1,1,1",
                                     "--goal", "5,5,1", "--out",   (dir.path() / name).string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const Run run = Aerobox(args);
    CAPTURE(run.err);
    CHECK(run.code == 0);
    return testing::ReadFile(dir.path() / name / "trajectory.csv");
  };
  // the same key, as --set and as its flag, on a map with no scenario: the same trajectory
  const std::string set = plan("set", {"--set", "trajectory.max_speed=1.0"});
  CHECK(set == plan("flag", {"--max-speed", "1.0"}));
  CHECK(set != plan("plain", {}));
  // a key the map alone cannot have is named as the setting
  const Run bad = Aerobox({"plan", room, "--set", "planner.max_stepp=0.5"});
  CHECK(bad.code == kExitBadInput);
  CHECK(bad.err.find("planner.max_stepp: in ") != std::string::npos);
  CHECK(bad.err.find("did you mean max_step?") != std::string::npos);
  // --trajectory given needs the scenario's trajectory file, as trajectory.method does
  const Run given = Aerobox({"fly", room, "--no-video", "--trajectory", "given"});
  CHECK(given.code == kExitBadInput);
  CHECK(given.err.find("--trajectory: \"given\" needs the trajectory's file") != std::string::npos);
}

}  // namespace aerobox

namespace aerobox {

TEST_CASE("check shows se3's position integral, on in wind") {
  const TempDir dir;
  dir.Write("room.txt", kRoom);
  const std::string windy =
      dir.Write("windy.toml",
                "map = \"room.txt\"\nstart = [1, 1, 1]\ngoal = [4, 4, 1]\n[controller]\n"
                "kind = \"se3\"\n[wind]\nmean = [2, 0, 0]\n");
  const Run run = Aerobox({"check", windy});
  CAPTURE(run.out);
  CHECK(run.out.find("position integral 12 12 12 1/s^3 (within 4 m/s^2)") != std::string::npos);
  const std::string still = dir.Write("still.toml",
                                      "map = \"room.txt\"\nstart = [1, 1, 1]\n"
                                      "goal = [4, 4, 1]\n[controller]\nkind = \"se3\"\n");
  CHECK(Aerobox({"check", still}).out.find("position integral") == std::string::npos);
}

TEST_CASE("check of several vehicles: each one's vehicle, controller and route, and the swarm") {
  const TempDir dir;
  dir.Write("room.txt", kRoom);
  const std::string scenario = dir.Write(
      "two.toml",
      "map = \"room.txt\"\n[swarm]\ndownwash = true\n"
      "[[vehicles]]\nname = \"a\"\nstart = [1, 1, 1]\ngoals = [[1, 4, 1], [4, 4, 1]]\n"
      "[[vehicles]]\nname = \"b\"\nkind = \"crazyflie\"\ncontroller = \"se3\"\nrate = 500\n"
      "start = [4, 1, 1]\ngoal = [1, 4, 1.5]\n");
  const Run run = Aerobox({"check", scenario});
  CAPTURE(run.out);
  CAPTURE(run.err);
  CHECK(run.code == kExitReachedGoal);
  CHECK(run.out.find("vehicles  2 in one world") != std::string::npos);
  CHECK(
      run.out.find("a: tello 0.08 kg, cascade at 250 Hz, (1, 1, 1) -> (1, 4, 1) -> (4, 4, 1) m") !=
      std::string::npos);
  CHECK(run.out.find("b: crazyflie 0.03 kg, se3 at 500 Hz, (4, 1, 1) -> (1, 4, 1.5) m") !=
        std::string::npos);
  CHECK(run.out.find("swarm     planning prioritised") != std::string::npos);
  CHECK(run.out.find("downwash on") != std::string::npos);
  // a vehicle's goal inside a box is named as the lone vehicle's is
  const std::string boxed =
      dir.Write("boxed.toml",
                "map = \"room.txt\"\n[[vehicles]]\nname = \"a\"\nstart = [1, 1, 1]\n"
                "goal = [2.5, 2.5, 1]\n");
  const Run bad = Aerobox({"check", boxed});
  CHECK(bad.code == kExitBadInput);
  CHECK(bad.err.find("goal (vehicle a, line 2)") != std::string::npos);
  // the vehicles give their own starts and goals: the command line cannot
  const Run moved = Aerobox({"fly", scenario, "--goal", "2,2,1", "--out", dir.path().string()});
  CHECK(moved.code == kExitBadInput);
  CHECK(moved.err.find("--goal: the scenario's [[vehicles]] give each vehicle its own") !=
        std::string::npos);
}

}  // namespace aerobox
