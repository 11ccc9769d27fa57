// aerobox-bench (run as `aerobox bench`): the performance tables of docs/benchmarks.md, each a
// measurement of ours against a reference in the same run. A separate binary, so that the
// product links neither Google Benchmark nor OMPL.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/city_benchmark.h"
#include "bench/flight_benchmark.h"
#include "bench/navigation_benchmark.h"
#include "bench/planner_comparison.h"
#include "bench/python_benchmark.h"
#include "bench/render_benchmark.h"
#include "bench/replanning_benchmark.h"
#include "bench/rigid_benchmark.h"
#include "bench/rl_benchmark.h"
#include "bench/robustness.h"
#include "bench/solver_comparison.h"
#include "bench/swarm_benchmark.h"
#include "bench/sweep_benchmark.h"
#include "common/error.h"
#include "common/progress.h"
#include "common/schema.h"
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

// What every section may need: the command's options, and the progress line.
struct BenchContext {
  std::string scenes, maps, city, robustness_csv;
  std::vector<std::string> controllers;  // robustness: the controllers flown
  int seeds = 20;
  double seconds = 1.0;
  BenchSize size;
  ProgressDisplay* progress = nullptr;

  std::string Scenario(const std::string& name) const {
    return (std::filesystem::path(scenes) / name / "scenario.toml").string();
  }
  std::vector<std::string> MapNames() const {
    std::vector<std::string> names;
    std::istringstream list(maps);
    std::string name;
    while (std::getline(list, name, ',')) names.push_back(name);
    return names;
  }
};

void PlanningSection(const BenchContext& c, std::ostream& out) {
  std::vector<PlanningProblem> problems;
  for (const std::string& name : c.MapNames()) {
    const std::string scenario = c.Scenario(name);
    const FlightSetup setup = LoadFlightSetup(scenario, {});
    if (!setup.goal) throw InputError({scenario, 0}, "goal", "the benchmark needs a goal");
    const CollisionWorld world(setup.map, setup.PlannerCollision());
    const auto [start, goal] = ResolveEndpoints(setup.map, world, setup.start, *setup.goal);
    problems.push_back({name, setup.map, start.used, goal.used});
  }
  out << "## RRT*: aerobox against OMPL " << (HaveOmpl() ? "1.5.2" : "(not built)") << ", "
      << c.seeds << " seeds, " << c.seconds << " s each\n\n";
  ComparePlanners(problems, c.seeds, c.seconds, out, *c.progress);
}

// A section: its name in --sections, and what prints its heading and its table.
struct BenchSection {
  const char* name;
  std::function<void(const BenchContext&, std::ostream&)> run;
};

const std::vector<BenchSection>& Sections() {
  static const std::vector<BenchSection> kSections = {
      {"trajectory",
       [](const BenchContext& c, std::ostream& out) {
         out << "## Minimum snap: Ipopt against the closed-form solve (medians of 5 "
                "repetitions)\n\n";
         CompareMinSnapSolvers(out, *c.progress, c.size);
       }},
      {"render",
       [](const BenchContext& c, std::ostream& out) {
         out << "## The video path against bare rendering on the window scene (60 frames, "
                "medians of 3)\n\n";
         CompareVideoPath(c.Scenario("window"), out, *c.progress, c.size);
       }},
      {"flight",
       [](const BenchContext& c, std::ostream& out) {
         out << "## Closed loop against bare mj_step on the window scene (medians of 5 "
                "repetitions)\n\n";
         CompareClosedLoop(c.Scenario("window"), out, *c.progress, c.size);
       }},
      {"speed",
       [](const BenchContext& c, std::ostream& out) {
         out << "## Flight time against a point-mass lower bound along the same path\n\n";
         SpeedTable(c.scenes, c.maps, out);
       }},
      {"python",
       [](const BenchContext& c, std::ostream& out) {
         out << "## A Python controller against the C++ ones (the aerobox package)\n\n"
             << std::flush;
         RunPythonBenchmark(c.Scenario("window"), out, c.size);
       }},
      {"rotorpy",
       [](const BenchContext& c, std::ostream& out) {
         out << "## RotorPy's Environment against aerobox.rotorpy's on the same scripts\n\n"
             << std::flush;
         RunRotorPyBenchmark(out, c.size);
       }},
      {"rl",
       [](const BenchContext& c, std::ostream& out) {
         out << "## Learning environments: steps per second against the bare physics\n\n"
             << std::flush;
         RunRlBenchmark(out, c.size);
         out << "\n";
         RunRigidBenchmark(out, c.size);
         out << "\n";
         RunRlPeers(out, c.size);
       }},
      {"robustness",
       [](const BenchContext& c, std::ostream& out) {
         RobustnessParams params;
         for (const std::string& map : c.MapNames()) params.scenarios.push_back(c.Scenario(map));
         params.seeds = c.seeds;
         params.csv = c.robustness_csv;
         params.controllers = c.controllers;
         out << "## Robustness: wind, turbulence, drag and sensors, " << c.seeds
             << " seeds per map, controller and wind\n\n";
         RobustnessTable(params, out, *c.progress);
         out << "\n";
         WindEightTable(params, out, *c.progress);
       }},
      {"replanning",
       [](const BenchContext& c, std::ostream& out) {
         std::vector<std::string> scenarios;
         for (const std::string& map : c.MapNames()) scenarios.push_back(c.Scenario(map));
         out << "## Replanning: 30 % of each map's boxes unknown until seen, " << c.seeds
             << " seeds per map\n\n";
         ReplanningTable(scenarios, c.seeds, 0.3, out, *c.progress);
       }},
      {"navigation",
       [](const BenchContext& c, std::ostream& out) {
         NavigationBenchParams params;
         params.scenario = c.Scenario("depth_forest");
         params.seeds = c.seeds;
         params.size = c.size;
         out << "## Navigation: unknown forests seen by the depth camera, " << c.seeds
             << " seeds per density\n\n";
         NavigationTable(params, out, *c.progress);
       }},
      {"sweep",
       [](const BenchContext& c, std::ostream& out) {
         out << "## Sweep throughput: aerobox sweep with one and two processes\n\n";
         SweepBenchmark(c.Scenario("window"), c.seeds, out, *c.progress);
       }},
      {"city",
       [](const BenchContext& c, std::ostream& out) {
         out << "## City scale: the FCND map, 50 queries 600-700 m apart\n\n";
         if (c.city.empty()) {
           out << "(skipped: give the map with --city FILE, e.g. the FCND colliders.csv)\n";
         } else {
           CityBenchmark(c.city, c.Scenario("window"), c.size.Count(50, 2), out, *c.progress,
                         c.size);
         }
       }},
      {"swarm",
       [](const BenchContext& c, std::ostream& out) {
         out << "## Several vehicles in one world: cost per vehicle, and the antipodal swap\n\n"
             << std::flush;
         RunSwarmBenchmark(c.Scenario("swarm_swap"), out, c.size);
       }},
      {"planning", PlanningSection},
  };
  return kSections;
}

std::vector<std::string> SectionNames() {
  std::vector<std::string> names;
  for (const BenchSection& section : Sections()) names.push_back(section.name);
  return names;
}

// The sections `list` names ("all", or names joined by commas), in the table's order; an
// unknown name is an InputError naming the one it looks like.
std::vector<const BenchSection*> Wanted(const std::string& list) {
  std::vector<std::string> asked;
  std::istringstream names(list);
  std::string name;
  while (std::getline(names, name, ',')) asked.push_back(name);
  const std::vector<std::string> known = SectionNames();
  for (const std::string& a : asked) {
    if (a == "all" || std::find(known.begin(), known.end(), a) != known.end()) continue;
    const std::string near = NearestName(a, known);
    throw InputError({"", 0}, "--sections",
                     "unknown section '" + a + "'" +
                         (near.empty() ? "" : " (did you mean '" + near + "'?)") +
                         "; sections: all, " + ListOfNames(known));
  }
  std::vector<const BenchSection*> wanted;
  for (const BenchSection& section : Sections()) {
    const bool all = std::find(asked.begin(), asked.end(), "all") != asked.end();
    if (all || std::find(asked.begin(), asked.end(), section.name) != asked.end()) {
      wanted.push_back(&section);
    }
  }
  return wanted;
}

int RunBench(const std::string& sections, BenchContext context, std::ostream& out,
             std::ostream& err) {
  const std::vector<const BenchSection*> wanted = Wanted(sections);  // before any work
  // a stage's line on a terminal, rewritten at most ten times a second; in a log, a line at
  // most every 10 s
  const bool terminal = ProgressDisplay::StderrIsTerminal();
  ProgressDisplay progress(err, terminal, terminal ? 0.1 : 10.0);
  context.progress = &progress;
  for (const BenchSection* section : wanted) {
    ThrowIfStopRequested("starting the next section (the tables above are complete)");
    section->run(context, out);
    out << "\n";
  }
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
  std::string names;
  for (const std::string& name : aerobox::SectionNames())
    names += (names.empty() ? "" : ",") + name;
  app.add_option("--sections", bench_sections, "all, or some of (comma-separated): " + names)
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
  std::string robustness_controllers = "cascade,se3,indi,cascade+observer,se3+observer";
  app.add_option("--controllers", robustness_controllers,
                 "robustness: the controllers flown, comma-separated kinds, each alone or with "
                 "+observer")
      ->capture_default_str();
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
  std::vector<std::string> controllers;
  try {
    aerobox::Wanted(bench_sections);  // every option before any work
    controllers = aerobox::RobustnessControllers(robustness_controllers);
  } catch (const std::invalid_argument& error) {
    std::cerr << "aerobox bench: error: --controllers: " << error.what() << "\n";
    return 2;
  } catch (const aerobox::InputError& error) {
    std::cerr << "aerobox bench: error: " << error.what() << "\n";
    return 2;
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
    aerobox::BenchContext context;
    context.scenes = bench_scenes;
    context.maps = bench_maps;
    context.city = bench_city;
    context.robustness_csv = robustness_csv;
    context.controllers = controllers;
    context.seeds = bench_seeds;
    context.seconds = bench_seconds;
    context.size = size;
    return aerobox::RunBench(bench_sections, context, std::cout, std::cerr);
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
