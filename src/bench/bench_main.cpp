// aerobox-bench (run as `aerobox bench`): the performance tables of docs/benchmarks.md, each a
// measurement of ours against a reference in the same run. A separate binary, so that the
// product links neither Google Benchmark nor OMPL.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "bench/city_benchmark.h"
#include "bench/flight_benchmark.h"
#include "bench/planner_comparison.h"
#include "bench/python_benchmark.h"
#include "bench/render_benchmark.h"
#include "bench/replanning_benchmark.h"
#include "bench/rl_benchmark.h"
#include "bench/robustness.h"
#include "bench/solver_comparison.h"
#include "bench/sweep_benchmark.h"
#include "common/error.h"
#include "common/progress.h"
#include "common/stop.h"
#include "geometry/collision_world.h"
#include "mission/mission.h"
#include "mission/plan.h"
#include "outputs/interrupt.h"
#include "planning/path_simplify.h"
#include "render/offscreen_context.h"
#include "scenario/scenario.h"
#include "trajectory/point_mass.h"
#include "trajectory/time_allocation.h"

namespace aerobox {
namespace {

// Per map: the flown time against two references with the vehicle's top speed (8 m/s, a
// Tello's) and the acceleration its tilt limit and thrust allow (ReachableAcceleration), in
// every direction:
// - the bound: the time-optimal point mass through the plan's waypoints, from rest to rest
//   (MinimumTimePointMass). The trajectory passes through the same waypoints, so no vehicle
//   with these limits flies it faster (up to Ipopt's local optimum);
// - the straight line: the path's length as one rest-to-rest trapezoid, as if corners cost
//   nothing (below the bound).
void SpeedTable(const std::string& scenes, const std::string& maps, std::ostream& out) {
  constexpr double kTopSpeed = 8.0;  // [m/s] a Tello's specification
  out << "| map | path [m] | flight [s] | bound [s] | flight / bound | straight line [s] | "
         "flight / straight line | average speed [m/s] | top speed [m/s] | peak rotor command "
         "[% of limit] |\n|---|---|---|---|---|---|---|---|---|---|\n";
  std::istringstream names(maps);
  std::string name;
  while (std::getline(names, name, ',')) {
    const std::string scenario = (std::filesystem::path(scenes) / name / "scenario.toml").string();
    const FlightSetup setup = LoadFlightSetup(scenario, {});
    const MissionResult result = RunMission(setup, MissionParts());
    if (!result.flown) {
      out << "| " << name << " | (" << ToString(result.status) << ") | | | | | | | | |\n";
      continue;
    }
    const std::vector<Vec3>& path = result.plan.result.path;
    const double length = PathLength(path);
    const double accel = ReachableAcceleration(setup);
    const double straight = TrapezoidTime(length, kTopSpeed, accel);
    PointMassParams limits;
    limits.max_speed = kTopSpeed;
    limits.max_accel = accel;
    const PointMassResult bound = MinimumTimePointMass(path, limits);
    const double time = result.flight.time;
    out << std::fixed << std::setprecision(2) << "| " << name << " | " << length << " | " << time
        << " | ";
    if (bound.solved) {
      out << bound.time << " | " << time / bound.time << " | ";
    } else {
      out << "(" << bound.message << ") | | ";
    }
    out << straight << " | " << time / straight << " | " << result.flight.AverageSpeed() << " | "
        << result.flight.top_speed << " | " << std::setprecision(0)
        << 100 * result.flight.peak_rotor_fraction << " |\n"
        << std::defaultfloat << std::flush;
  }
}

int RunBench(const std::string& sections, const std::string& scenes, const std::string& maps,
             const std::string& city, int seeds, double seconds, const std::string& robustness_csv,
             const BenchSize& size, std::ostream& out, std::ostream& err) {
  // a stage's line on a terminal, rewritten at most ten times a second; in a log, a line at
  // most every 10 s
  const bool terminal = ProgressDisplay::StderrIsTerminal();
  ProgressDisplay progress(err, terminal, terminal ? 0.1 : 10.0);
  const auto wanted = [&sections](const char* name) {
    ThrowIfStopRequested("starting the next section (the tables above are complete)");
    return sections == "all" ||
           ("," + sections + ",").find(std::string(",") + name + ",") != std::string::npos;
  };
  if (wanted("trajectory")) {
    out << "## Minimum snap: Ipopt against the closed-form solve (medians of 5 repetitions)\n\n";
    CompareMinSnapSolvers(out, progress, size);
    out << "\n";
  }
  if (wanted("render")) {
    const std::string window =
        (std::filesystem::path(scenes) / "window" / "scenario.toml").string();
    out << "## The video path against bare rendering on the window scene (60 frames, medians of "
           "3)\n\n";
    CompareVideoPath(window, out, progress, size);
    out << "\n";
  }
  if (wanted("flight")) {
    const std::string window =
        (std::filesystem::path(scenes) / "window" / "scenario.toml").string();
    out << "## Closed loop against bare mj_step on the window scene (medians of 5 repetitions)\n\n";
    CompareClosedLoop(window, out, progress, size);
    out << "\n";
  }
  if (wanted("speed")) {
    out << "## Flight time against a point-mass lower bound along the same path\n\n";
    SpeedTable(scenes, maps, out);
    out << "\n";
  }
  if (wanted("python")) {
    out << "## A Python controller against the C++ ones (the aerobox package)\n\n" << std::flush;
    const std::string window =
        (std::filesystem::path(scenes) / "window" / "scenario.toml").string();
    RunPythonBenchmark(window, out, size);
    out << "\n";
  }
  if (wanted("rotorpy")) {
    out << "## RotorPy's Environment against aerobox.rotorpy's on the same scripts\n\n"
        << std::flush;
    RunRotorPyBenchmark(out, size);
    out << "\n";
  }
  if (wanted("rl")) {
    out << "## Learning environments: steps per second against the bare physics\n\n" << std::flush;
    RunRlBenchmark(out, size);
    out << "\n";
  }
  if (wanted("robustness")) {
    RobustnessParams params;
    std::istringstream list(maps);
    std::string map;
    while (std::getline(list, map, ',')) {
      params.scenarios.push_back((std::filesystem::path(scenes) / map / "scenario.toml").string());
    }
    params.seeds = seeds;
    params.csv = robustness_csv;
    out << "## Robustness: wind, turbulence, drag and sensors, " << seeds
        << " seeds per map and wind\n\n";
    RobustnessTable(params, out, progress);
    out << "\n";
  }
  if (wanted("replanning")) {
    std::vector<std::string> scenarios;
    std::istringstream list(maps);
    std::string map;
    while (std::getline(list, map, ',')) {
      scenarios.push_back((std::filesystem::path(scenes) / map / "scenario.toml").string());
    }
    out << "## Replanning: 30 % of each map's boxes unknown until seen, " << seeds
        << " seeds per map\n\n";
    ReplanningTable(scenarios, seeds, 0.3, out, progress);
    out << "\n";
  }
  if (wanted("sweep")) {
    out << "## Sweep throughput: aerobox sweep with one and two processes\n\n";
    SweepBenchmark((std::filesystem::path(scenes) / "window" / "scenario.toml").string(), seeds,
                   out, progress);
    out << "\n";
  }
  if (wanted("city")) {
    out << "## City scale: the FCND map, 50 queries 600-700 m apart\n\n";
    if (city.empty()) {
      out << "(skipped: give the map with --city FILE, e.g. the FCND colliders.csv)\n\n";
    } else {
      const std::string window =
          (std::filesystem::path(scenes) / "window" / "scenario.toml").string();
      CityBenchmark(city, window, size.Count(50, 2), out, progress, size);
      out << "\n";
    }
  }
  if (!wanted("planning")) return 0;
  std::vector<PlanningProblem> problems;
  std::istringstream names(maps);
  std::string name;
  while (std::getline(names, name, ',')) {
    const std::string scenario = (std::filesystem::path(scenes) / name / "scenario.toml").string();
    const FlightSetup setup = LoadFlightSetup(scenario, {});
    if (!setup.goal) throw InputError({scenario, 0}, "goal", "the benchmark needs a goal");
    const CollisionWorld world(setup.map, setup.PlannerCollision());
    const auto [start, goal] = ResolveEndpoints(setup.map, world, setup.start, *setup.goal);
    problems.push_back({name, setup.map, start.used, goal.used});
  }
  out << "## RRT*: aerobox against OMPL " << (HaveOmpl() ? "1.5.2" : "(not built)") << ", " << seeds
      << " seeds, " << seconds << " s each\n\n";
  ComparePlanners(problems, seeds, seconds, out, progress);
  return 0;
}

}  // namespace
}  // namespace aerobox

int main(int argc, char** argv) {
  CLI::App app("aerobox bench: performance tables, each against a reference in the same run",
               "aerobox bench");
  std::string bench_sections = "all";
  std::string bench_scenes = "scenes";
  std::string bench_maps = "window,maze,forest,over_under";
  int bench_seeds = 20;
  double bench_seconds = 1.0;
  app.add_option("--sections", bench_sections,
                 "all, or some of: "
                 "trajectory,flight,render,speed,python,rotorpy,rl,robustness,replanning,sweep,"
                 "city,planning")
      ->capture_default_str();
  app.add_option("--scenes", bench_scenes, "folder with the scenes")->capture_default_str();
  app.add_option("--maps", bench_maps, "comma-separated scene names")->capture_default_str();
  std::string bench_city;
  app.add_option("--city", bench_city, "the city map for the city section (FCND CSV)")
      ->check(CLI::ExistingFile);
  std::string robustness_csv;
  app.add_option("--robustness-csv", robustness_csv,
                 "robustness: also write one row per flight to this CSV (tools/plot_robustness.py "
                 "plots it)");
  app.add_option("--seeds", bench_seeds, "runs per planner and map (planning, robustness)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  app.add_option("--seconds", bench_seconds, "time budget of each run [s]")
      ->capture_default_str()
      ->check(CLI::Range(0.2, 60.0));
  aerobox::BenchSize size;
  app.add_flag("--smoke", size.smoke,
               "a smoke run: every section at its smallest (one repetition; unless given, "
               "--maps window --seeds 1 --seconds 0.2); shows that each section runs, its "
               "numbers mean nothing");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error) == 0 ? 0 : 2;
  }
  if (size.smoke) {
    if (app.count("--maps") == 0) bench_maps = "window";
    if (app.count("--seeds") == 0) bench_seeds = 1;
    if (app.count("--seconds") == 0) bench_seconds = 0.2;
    std::cout << "(a smoke run: one repetition, the smallest sizes; it shows that every section "
                 "runs, and its numbers mean nothing)\n\n";
  }
  // Ctrl-C: every section stops at its next check, exit 130 (outputs/interrupt.h)
  aerobox::DisableShaderDiskCache();  // its thread would hold up an interrupted process's end
  aerobox::InstallInterruptHandler();
  try {
    if (!robustness_csv.empty()) {
      // checked before any work: its folder exists
      const std::filesystem::path folder = std::filesystem::absolute(robustness_csv).parent_path();
      if (!std::filesystem::is_directory(folder)) {
        throw aerobox::InputError({robustness_csv, 0}, "--robustness-csv",
                                  "its folder does not exist");
      }
    }
    return aerobox::RunBench(bench_sections, bench_scenes, bench_maps, bench_city, bench_seeds,
                             bench_seconds, robustness_csv, size, std::cout, std::cerr);
  } catch (const aerobox::Interrupted& stop) {
    std::cout << std::flush;
    std::cerr << "\naerobox bench: interrupted while " << stop.during()
              << "; the tables printed above are complete\n";
    return aerobox::kInterruptedExitCode;
  } catch (const aerobox::InputError& error) {
    std::cerr << "aerobox bench: error: " << error.what() << "\n";
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "aerobox bench: unexpected error: " << error.what() << "\n";
    return 1;
  }
}
