#include "app/cli.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <csignal>
#include <filesystem>
#include <iomanip>
#include <optional>
#include <sstream>

#include "app/compare_job.h"
#include "app/exit_codes.h"
#include "app/fly_job.h"
#include "app/sweep_job.h"
#include "common/error.h"
#include "common/fault_injection.h"
#include "common/number_format.h"
#include "common/quoting.h"
#include "common/subprocess.h"
#include "map/forest.h"
#include "mission/plan.h"
#include "outputs/files.h"
#include "outputs/interrupt.h"
#include "python/embedded.h"
#include "scenario/scenario.h"
#include "scenario/sweep.h"
#include "scene/scene_mjcf.h"
#include "sim/simulation.h"
#include "telemetry/csv_table.h"

namespace aerobox {
namespace {

// The faults a fault test injects (AEROBOX_FAULT, common/fault_injection.h): read here, in the
// command, and obeyed by the domain (FlightSetup::faults), which reads no environment.
void ReadInjectedFaults(FlightSetup* setup) {
  if (const std::optional<std::string> at = InjectedFault("nonfinite")) {
    double from = 0.0;
    if (!ParseNumber(*at, &from)) from = 0.0;
    setup->faults.nonfinite_setpoint_from = from;
  }
  setup->faults.ipopt_failure = InjectedFault("ipopt").has_value();
}

// "X,Y,Z" from the command line [m].
std::optional<Vec3> ParsePointOption(const std::string& text, const char* option,
                                     const char* unit = "metres") {
  if (text.empty()) return std::nullopt;
  Vec3 point;
  std::istringstream fields(text);
  std::string field;
  int count = 0;
  while (std::getline(fields, field, ',')) {
    if (count < 3 && ParseNumber(field, &point[count]) && std::isfinite(point[count])) {
      ++count;
    } else {
      count = 4;
      break;
    }
  }
  if (count != 3) {
    throw InputError(
        {"command line", 0}, option,
        std::string("expected three numbers X,Y,Z in ") + unit + ", got '" + text + "'");
  }
  return point;
}

const char* FormatName(MapFormat format) {
  switch (format) {
    case MapFormat::kTxt:
      return "TXT";
    case MapFormat::kJson:
      return "JSON";
    case MapFormat::kCsv:
      return "CSV";
  }
  return "?";
}

std::string Describe(const Aabb& box) {
  return "[" + FormatVector(box.min, ", ") + "] .. [" + FormatVector(box.max, ", ") + "]";
}

// Start and goal must lie inside the bounds (on them is allowed: published maps do it) and
// outside every box.
void CheckEndpoint(const FlightSetup& setup, const Vec3& point, const std::string& what,
                   const std::string& origin) {
  const std::string field = what + " (" + origin + ")";
  const SourceLocation where{setup.map.source, 0};
  if (!setup.map.bounds.Contains(point)) {
    throw InputError(
        where, field,
        FormatVector(point, ", ") + " lies outside the bounds " + Describe(setup.map.bounds));
  }
  if (const auto box = FirstOverlappingBox(setup.map, Aabb{point, point})) {
    const Box& b = setup.map.boxes[*box];
    throw InputError(
        {setup.map.source, b.line}, field,
        FormatVector(point, ", ") + " lies inside " + b.name + " " + Describe(b.extent));
  }
}

// The boxes found in flight, the sensor that finds them and how the flight replans, in words.
std::string DescribeUnknownBoxes(const FlightSetup& setup) {
  if (!setup.HasUnknown()) return "none: the planner knows every box";
  const long unknown = std::count(setup.unknown.begin(), setup.unknown.end(), true);
  const SensingParams& sensing = setup.sensing;
  const ReplanParams& r = setup.replan;
  std::ostringstream out;
  out << unknown << " of " << setup.map.boxes.size() << " boxes, found in flight by ";
  if (sensing.kind == SensingParams::Kind::kCamera) {
    out << "a depth camera along body x (" << FormatNumber(sensing.fov_horizontal) << " x "
        << FormatNumber(sensing.fov_vertical) << " rad; whole boxes, through walls)";
  } else if (sensing.kind == SensingParams::Kind::kDepth) {
    out << "a depth camera along body x (" << FormatNumber(sensing.fov_horizontal) << " x "
        << FormatNumber(sensing.fov_vertical) << " rad, " << sensing.camera.width << " x "
        << sensing.camera.height << " px; line of sight) into a "
        << FormatNumber(sensing.map.resolution) << " m occupancy map";
  } else {
    out << "a range sensor all round";
  }
  out << ", " << FormatNumber(sensing.range) << " m at " << FormatNumber(sensing.rate)
      << " Hz; replanning " << FormatNumber(r.horizon) << " s ahead, RRT* at most "
      << r.search_iterations << " iterations to a first solution and " << r.iterations
      << " after it (a " << FormatNumber(r.time_budget) << " s safety cap), " << r.max_attempts
      << " attempts while braked";
  return out.str();
}

// `aerobox forest`: a seeded forest written as a map; a bad value is named by its option.
int RunForest(const ForestParams& params, const std::string& output, std::ostream& out,
              std::ostream& err) {
  Map forest;
  try {
    forest = MakeForest(params);
  } catch (const std::invalid_argument& error) {
    std::string message = error.what();  // "forest.width_max: ..." -> "--width-max: ..."
    const size_t key = message.find("forest.");
    if (key != std::string::npos) {
      const size_t end = message.find_first_of(": ", key);
      std::string option = message.substr(key + 7, end - key - 7);
      std::replace(option.begin(), option.end(), '_', '-');
      message.replace(key, end - key, "--" + option);
    }
    throw InputError({"command line", 0}, "", message);
  }
  const std::string text = MapJson(forest);
  if (output.empty() || output == "-") {
    out << text;
  } else {
    WriteFileAtomically(output, text);
    err << "forest: " << params.pillars << " pillars and " << params.bars << " bars in "
        << FormatVector(params.size, " x ") << " m, seed " << params.seed << ", written to "
        << output << "\n";
  }
  return kExitReachedGoal;
}

std::ostream& Row(std::ostream& out, const char* label) {
  return out << std::left << std::setw(10) << label;
}

// check's rows on the map and where the flight starts and ends.
void CheckPlaces(const FlightSetup& setup, std::ostream& out) {
  const Map& map = setup.map;
  Row(out, "map") << map.source << " (" << FormatName(setup.map_format) << ")\n";
  Row(out, "name") << setup.name << "\n";
  Row(out, "bounds") << Describe(map.bounds) << " m (" << FormatVector(map.bounds.Size(), " x ")
                     << " m)\n";
  Row(out, "boxes") << map.boxes.size() << "\n";
  if (setup.start_origin == kNoStart) {
    Row(out, "start") << "none: no start given and no free spot on the floor or a block\n";
  } else {
    Row(out, "start") << FormatVector(setup.start, ", ") << " (" << setup.start_origin << ")\n";
  }
  if (setup.goal) {
    Row(out, "goal") << FormatVector(*setup.goal, ", ") << " (" << setup.goal_origin << ")\n";
  } else {
    Row(out, "goal") << "none given\n";
  }
}

std::string DescribeVehicle(const std::string& kind, const QuadParams& v) {
  std::ostringstream out;
  out << kind << ": " << FormatNumber(v.mass) << " kg, inertia " << FormatVector(v.inertia)
      << " kg m^2, rotors " << FormatNumber(v.MinRotorThrust()) << " .. "
      << FormatNumber(v.MaxRotorThrust()) << " N (thrust/weight "
      << FormatNumber(std::round(100 * kNumRotors * v.MaxRotorThrust() / (v.mass * kGravity)) / 100)
      << "), yaw " << FormatNumber(v.yaw_moment_per_thrust) << " N m/N, motor lag "
      << FormatNumber(v.motor_time_constant) << " s, box " << FormatVector(v.collision_size, " x ")
      << " m";
  return out.str();
}

std::string DescribeControl(const FlightSetup& setup) {
  const ControllerConfig& c = setup.controller;
  std::ostringstream out;
  out << c.kind << " at " << FormatNumber(c.rate) << " Hz: ";
  if (c.observer.enabled) {
    out << "disturbance observer (" << FormatNumber(c.observer.time_constant) << " s); ";
  }
  if (const std::string measures = setup.ControllerMeasures(); !measures.empty()) {
    out << "measures: " << measures << "; ";
  }
  if (c.kind == "cascade") {
    out << "position " << FormatVector(c.cascade.position_gain) << " 1/s, velocity "
        << FormatVector(c.cascade.velocity_gain) << " 1/s (I "
        << FormatVector(c.cascade.velocity_integral)
        << " 1/s^2), tilt <= " << FormatNumber(c.cascade.max_tilt) << " rad; ";
  } else if (c.kind == "se3") {
    out << "position " << FormatVector(c.se3.position_gain) << " 1/s^2, velocity "
        << FormatVector(c.se3.velocity_gain) << " 1/s, attitude "
        << FormatVector(c.se3.attitude_gain) << " 1/s^2, rates " << FormatVector(c.se3.rate_gain)
        << " 1/s; ";
    if (!c.se3.position_integral.isZero()) {
      out << "position integral " << FormatVector(c.se3.position_integral) << " 1/s^3 (within "
          << FormatNumber(c.se3.integral_limit) << " m/s^2); ";
    }
  }
  out << "inner loops: attitude " << FormatVector(c.inner.attitude.gain) << " 1/s, rates "
      << FormatVector(c.inner.rate.gain) << " 1/s";
  return out.str();
}

std::string DescribeAir(const FlightSetup& setup) {
  const WindParams& w = setup.wind;
  if (!w.Enabled() && !setup.aero.Enabled()) return "still, no drag";
  std::ostringstream out;
  out << "wind " << FormatVector(w.mean) << " m/s";
  if (w.turbulence == Turbulence::kDryden) {
    out << ", Dryden turbulence " << FormatVector(w.intensity) << " m/s";
  }
  if (!w.gusts.empty()) out << ", " << w.gusts.size() << " gust(s)";
  out << "; drag: body " << (setup.aero.body_drag ? "on" : "off") << ", rotor "
      << (setup.aero.rotor_drag ? "on" : "off")
      << (MeasuresAcceleration(setup.controller) ? ", measured by the controller"
          : setup.controller.drag_feedforward    ? ", fed forward by the controller"
                                                 : "");
  return out.str();
}

std::string DescribeSensors(const SensorParams& sensors) {
  if (!sensors.Enabled()) return "none: the controller reads the true state";
  const PositionSensorParams& pos = sensors.position;
  std::ostringstream out;
  out << "IMU at " << FormatNumber(sensors.imu.rate) << " Hz, "
      << (pos.kind == PositionSensorKind::kGps ? "GPS" : "motion capture") << " at "
      << FormatNumber(pos.rate) << " Hz (noise " << FormatVector(pos.noise) << " m, latency "
      << FormatNumber(pos.latency) << " s); the controller flies on the estimator's state";
  return out.str();
}

std::string DescribePlanning(const FlightSetup& setup) {
  const PlanningSettings& p = setup.planning;
  // a cap that is not set (min-time: the vehicle's limits decide) reads "no ... cap", not "inf"
  const auto cap = [](double value, const char* unit, const char* what) {
    return std::isfinite(value) ? FormatNumber(value) + " " + unit
                                : std::string("no ") + what + " cap";
  };
  return PlannerKindFor(setup) + ", clearance " + FormatNumber(p.clearance) + " m; trajectory " +
         p.trajectory_method + ", " + cap(p.trajectory.max_speed, "m/s", "speed") + ", " +
         cap(p.trajectory.max_accel, "m/s^2", "acceleration") + ", clearance " +
         FormatNumber(p.trajectory_clearance) + " m";
}

// check's rows on the boxes outside the bounds, and on the start and goal as planning takes
// them; throws InputError for an endpoint that cannot be flown from or to.
void CheckEndpoints(const FlightSetup& setup, std::ostream& out) {
  const Map& map = setup.map;
  const std::vector<size_t> outside = BoxesOutsideBounds(map);
  Row(out, "outside") << outside.size() << (outside.size() == 1 ? " box reaches" : " boxes reach")
                      << " outside the bounds (kept)\n";
  for (const size_t i : outside) {
    out << "            " << map.boxes[i].name << " (line " << map.boxes[i].line
        << "): " << Describe(map.boxes[i].extent) << "\n";
  }
  if (setup.start_origin != kNoStart) {
    CheckEndpoint(setup, setup.start, "start", setup.start_origin);
  }
  if (setup.goal) CheckEndpoint(setup, *setup.goal, "goal", setup.goal_origin);
  // where planning will take them: moved off the floor or the walls, out of the clearance
  if (setup.goal && setup.start_origin != kNoStart) {
    const CollisionWorld world(setup.map, setup.PlannerCollision());
    const auto [start, goal] = ResolveEndpoints(setup.map, world, setup.start, *setup.goal,
                                                setup.start_where, setup.goal_where);
    out << DescribeMoves(start, goal);
  }
}

// Several vehicles: each one's vehicle, controller and route (its points checked as the start
// and goal are, then where planning takes them), and how they keep apart.
void CheckVehicles(const FlightSetup& setup, std::ostream& out) {
  Row(out, "vehicles") << setup.vehicles.size() << " in one world ([[vehicles]]):\n";
  for (size_t i = 0; i < setup.vehicles.size(); ++i) {
    const FlightSetup member = setup.Member(i);
    out << "            " << member.name << ": " << member.vehicle_kind << " "
        << FormatNumber(member.vehicle.mass) << " kg, " << member.controller.kind << " at "
        << FormatNumber(member.controller.rate) << " Hz, (" << FormatVector(member.start, ", ");
    for (const Vec3& p : member.via) out << ") -> (" << FormatVector(p, ", ");
    out << ") -> (" << FormatVector(*member.goal, ", ") << ") m\n";
    const std::string at =
        "vehicle " + member.name + ", line " + std::to_string(setup.vehicles[i].where.line);
    CheckEndpoint(member, member.start, "start", at);
    for (const Vec3& p : member.via) CheckEndpoint(member, p, "goals", at);
    CheckEndpoint(member, *member.goal, "goal", at);
  }
  const SwarmParams& s = setup.swarm;
  Row(out, "swarm") << "planning " << s.planning << ", " << FormatNumber(s.separation)
                    << " m kept beyond both radii, waits of " << FormatNumber(s.wait_step)
                    << " s up to " << FormatNumber(s.max_wait) << " s; downwash "
                    << (s.downwash ? "on" : "off") << "\n";
}

int RunCheck(const FlightSetup& setup, std::ostream& out) {
  CheckPlaces(setup, out);
  // the settings in force, after the scenario's tables
  const FlightParams& f = setup.flight;
  Row(out, "vehicle") << DescribeVehicle(setup.vehicle_kind, setup.vehicle) << "\n";
  Row(out, "control") << DescribeControl(setup) << "\n";
  Row(out, "flight") << "goal within " << FormatNumber(f.goal_tolerance) << " m below "
                     << FormatNumber(f.goal_speed) << " m/s, " << FormatNumber(f.settle_time)
                     << " s after the trajectory; fly-away at " << FormatNumber(f.flyaway_distance)
                     << " m; yaw " << (f.face_travel ? "along the travel" : "held") << "\n";
  Row(out, "air") << DescribeAir(setup) << "\n";
  Row(out, "sensors") << DescribeSensors(setup.sensors) << "\n";
  Row(out, "planner") << DescribePlanning(setup) << "\n";
  Row(out, "unknown") << DescribeUnknownBoxes(setup) << "\n";
  if (!setup.vehicles.empty()) CheckVehicles(setup, out);
  CheckEndpoints(setup, out);
  const Simulation sim = Simulation::FromXml(SceneMjcfFor(setup), setup.map.source + " (scene)");
  Row(out, "scene") << "loads in MuJoCo " << mj_versionString() << " (" << sim.model()->ngeom
                    << " geoms, " << sim.model()->nbody << " bodies)\n";
  Row(out, "result") << "ok\n";
  return kExitReachedGoal;
}

int RunScene(const FlightSetup& setup, const std::string& output, std::ostream& out) {
  const std::string xml = SceneMjcfFor(setup);
  if (output.empty() || output == "-") {
    out << xml;
  } else {
    WriteFileAtomically(output, xml);
  }
  return kExitReachedGoal;
}

// Plans into `output`'s staging folder; RunPlan commits it.
int PlanInto(const FlightSetup& setup, const OutputFolder& output, std::ostream& out,
             std::ostream& err) {
  if (const std::string warning = LimitsWarning(setup); !warning.empty()) {
    out << "warning: " << warning << "\n";
  }
  err << "plan " << setup.name << ": planning\n";
  const PlanOutcome plan = PlanFlight(setup);
  const std::filesystem::path folder(output.staging());
  out << DescribeMoves(plan.start, plan.goal);
  const PlanStats& stats = plan.result.stats;
  std::ostringstream timing;
  timing << std::fixed << std::setprecision(3) << stats.planning_time;
  if (plan.result.status != PlanStatus::kSolved) {
    out << "plan " << setup.name << ": " << ToString(plan.result.status) << " after "
        << stats.iterations << " iterations (" << timing.str() << " s), seed " << setup.seed
        << "\n";
    if (plan.result.status == PlanStatus::kPathBlocked) {
      out << "  " << DescribeBlockedPath(plan) << "\n";
    }
    return plan.result.status == PlanStatus::kNoPathWithinBudget ||
                   plan.result.status == PlanStatus::kPathBlocked
               ? kExitNoPath
               : kExitBadInput;
  }
  if (plan.lattice) {
    out << std::fixed << std::setprecision(3) << "lattice: " << plan.lattice->nodes << " nodes, "
        << plan.lattice->edges << " edges, built in " << plan.lattice->build_time << " s\n";
  }
  const std::string path_file = (std::filesystem::path(output.path()) / "path.csv").string();
  WriteFileAtomically((folder / "path.csv").string(), PathCsv(plan.result.path));
  std::ostringstream line;
  line << std::fixed << std::setprecision(2) << "plan " << setup.name << ": solved, "
       << plan.result.path.size() << " waypoints, " << stats.final_cost << " m ";
  if (plan.fallback_spacing > 0) {
    line << "by a " << plan.fallback_spacing << " m lattice after RRT* found no path in "
         << stats.iterations << " iterations, ";
  } else {
    line << "(first solution " << stats.first_cost << " m after " << std::setprecision(1)
         << 1e3 * stats.time_to_first_solution << " ms), " << stats.iterations << " iterations, ";
  }
  line << "in " << timing.str() << " s, seed " << setup.seed << " -> " << path_file << "\n";
  out << line.str();

  const TrajectoryResult& trajectory = *plan.trajectory;
  const TrajectoryStats& t = trajectory.stats;
  std::ostringstream summary;
  summary << std::fixed << std::setprecision(2) << "trajectory: " << ToString(trajectory.status)
          << " (" << t.solver_message << "), " << t.segments << " segments, " << t.refinements
          << " refinements, " << 1e3 * t.solve_time << " ms";
  if (trajectory.status != TrajectoryStatus::kSolved) {
    out << summary.str() << "\n";
    return kExitNoTrajectory;
  }
  const std::string trajectory_file =
      (std::filesystem::path(output.path()) / "trajectory.csv").string();
  WriteFileAtomically((folder / "trajectory.csv").string(), TrajectoryCsv(trajectory.trajectory));
  summary << "; " << t.duration << " s, max " << t.max_speed << " m/s, " << t.max_accel
          << " m/s^2 -> " << trajectory_file << "\n";
  out << summary.str();
  return kExitReachedGoal;
}

int RunPlan(const FlightSetup& setup, const std::string& out_dir, std::ostream& out,
            std::ostream& err) {
  OutputFolder output(out_dir, setup.name);
  const int code = output.Run([&] { return PlanInto(setup, output, out, err); });
  output.Commit();  // the folder holds this run's outputs only
  return code;
}

// `aerobox bench ARGS...`: the benchmarks are a separate binary, aerobox-bench beside this one,
// so that the product links neither Google Benchmark nor OMPL. Its exit code is ours.
int RunBenchBinary(const std::vector<std::string>& args, std::ostream& err) {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::filesystem::path binary = self.parent_path() / "aerobox-bench";
  if (ec || !std::filesystem::exists(binary)) {
    err << "aerobox: error: bench: " << binary.string()
        << " is missing (build the aerobox-bench target)\n";
    return kExitBadInput;
  }
  ProcessSpec spec;
  spec.argv = {binary.string()};
  spec.argv.insert(spec.argv.end(), args.begin(), args.end());
  // Ctrl-C reaches the child too from a terminal; a SIGINT sent to this process alone is
  // passed on (RunProcess), so that the benchmark never outlives the command
  const int code = RunProcess(spec);
  return StopRequested() ? kExitInterrupted : code;
}

// The command line as a shell reads it, for report.html.
std::string RepeatCommand(int argc, const char* const* argv) {
  std::string command = "aerobox";
  for (int i = 1; i < argc; ++i) command += " " + ShellQuoted(argv[i]);
  return command;
}

int RunModel(const std::string& output, std::ostream& out) {
  const std::string xml = VehicleModelMjcf(QuadParams());
  if (output.empty() || output == "-") {
    out << xml;
  } else {
    WriteFileAtomically(output, xml);
  }
  return kExitReachedGoal;
}

// The command line: every command, its options, and the run of the one given.
class Cli {
 public:
  Cli() {
    app.set_version_flag("--version", std::string("aerobox ") + AEROBOX_VERSION + " (MuJoCo " +
                                          mj_versionString() + ")");
    app.require_subcommand(1);
    AddInputCommands();
    AddFlyCommand();
    AddCheckAndCompare();
    AddSweepCommands();
  }

  int Run(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& error) {
      const int code = app.exit(error, out, err);
      return code == 0 ? kExitReachedGoal : kExitBadInput;
    }
    try {
      return Dispatch(argc, argv, out, err);
    } catch (const Interrupted& stop) {
      // every output folder is as it was: a run's files are moved in only when it has ended
      err << "\naerobox: " << stop.what() << "; no output written or changed\n";
      return kExitInterrupted;
    } catch (const InputError& error) {
      err << "aerobox: error: " << error.what() << "\n";
      return kExitBadInput;
    } catch (const std::invalid_argument& error) {
      err << "aerobox: error: " << error.what() << "\n";
      return kExitBadInput;
    } catch (const std::exception& error) {
      err << "aerobox: unexpected error: " << error.what() << "\n";
      return kExitUnexpected;
    }
  }

 private:
  // input, --start, --goal, --set: a command that reads a scenario or a map
  void AddInput(CLI::App* command) {
    command->add_option("input", input, "scenario.toml or map file (.txt, .json, .csv)")
        ->required();
    command->add_option("--start", start_text, "start X,Y,Z [m], overriding the scenario's");
    command
        ->add_option("--goal", goal_texts,
                     "goal X,Y,Z [m], overriding the scenario's; several: a mission through "
                     "each in order")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    command
        ->add_option("--set", set_texts,
                     "set a scenario key, KEY=VALUE with a TOML value: trajectory.max_speed=2.0, "
                     "controller.kind=se3; may be given several times; also on a bare map")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  }

  // scene, plan, bench
  void AddInputCommands() {
    scene = app.add_subcommand("scene", "write the MuJoCo MJCF scene of a map");
    AddInput(scene);
    scene->add_option("-o,--output", output, "output file (default: standard output)");

    plan = app.add_subcommand(
        "plan", "plan a path (RRT*) and a trajectory (min-snap); write path.csv, trajectory.csv");
    AddInput(plan);
    plan->add_option("--out", out_dir, "output folder (default: renders/<scenario name>/)");
    plan->add_option("--seed", seed, "random seed (default: the scenario's, else 1)")
        ->each([this](const std::string&) { seed_given = true; });

    bench = app.add_subcommand(
        "bench",
        "performance tables (runs aerobox-bench, installed beside aerobox; see its --help)");
    bench->prefix_command();  // everything after "bench" goes to aerobox-bench as it is
    bench->set_help_flag();
    bench->allow_extras();
  }

  void AddFlyCommand() {
    fly = app.add_subcommand(
        "fly",
        "plan, solve and fly a scenario in MuJoCo; write path, trajectory, telemetry, summary");
    AddInput(fly);
    fly->add_option("--out", out_dir, "output folder (default: renders/<scenario name>/)");
    fly->add_option("--seed", seed, "random seed (default: the scenario's, else 1)")
        ->each([this](const std::string&) { seed_given = true; });
    fly->add_flag("--no-video", no_video, "do not write video.mp4");
    fly->add_flag("--no-overview", no_overview, "do not write overview.png");
    fly->add_flag("--no-telemetry", no_telemetry, "do not write telemetry.csv");
    fly->add_flag("--no-report", no_report,
                  "do not write report.html (the run in 3-D and in charts, for a browser)");
    fly->add_option("--size", size, "video size WxH, at most 1920x1080")->capture_default_str();
    fly->add_option("--fps", fly_options.fps, "video frames per second")->capture_default_str();
    fly->add_option("--playback,--speed", fly_options.speed,
                    "video playback speed (2: the video shows the flight twice as fast); not the "
                    "vehicle's speed, which is --max-speed")
        ->capture_default_str();
    fly->add_option("--camera", fly_options.camera, "chase, overview or top")
        ->capture_default_str();
    fly->add_option("--quality", fly_options.quality, "fast or pretty")->capture_default_str();
    fly->add_flag("--quiet", quiet, "no progress line");
    fly->add_flag("--show-tree", fly_options.show_tree,
                  "draw the RRT* tree: growing in the video's first 3 s, whole in overview.png");
    fly->add_option("--trajectory", trajectory_method,
                    "minsnap (default), a baseline on its waypoints and times: quintic, cubic, "
                    "septic-full; or given (the scenario's [trajectory] file)");
    fly->add_option(
        "--controller", python_modules.controller,
        "the controller: a built-in (cascade, se3, indi) or a Python class, file.py:Class "
        "(Class(quad_params).update(t, state, flat_output) -> dict, RotorPy's contract)");
    fly->add_option("--command", python_modules.command,
                    "which keys of a Python controller's dict fly: auto (the lowest level given), "
                    "cmd_motor_thrusts, cmd_motor_speeds, cmd_ctbm, cmd_ctbr or cmd_ctatt")
        ->capture_default_str();
    fly->add_option("--trajectory-module", python_modules.trajectory,
                    "a Python trajectory class, file.py:Class: Class(path) with update(t) -> "
                    "flat_output and a duration [s]");
    fly->add_option("--planner-module", python_modules.planner,
                    "a Python planner class, file.py:Class: Class().plan(world, start, goal) -> "
                    "(N, 3) waypoints [m]");
    fly->add_option("--wind", wind_text,
                    "mean wind X,Y,Z [m/s], world frame ([wind] mean); brings drag unless [aero] "
                    "turns it off");
    fly->add_option("--turbulence", turbulence,
                    "Dryden turbulence of this standard deviation on every axis [m/s]; 0: none "
                    "([wind] turbulence and intensity)");
    fly->add_option("--frames-every", fly_options.frames_every,
                    "also write frames/frame_NNNNNN.png every this many seconds of flight");
  }

  // the trajectory's caps for plan and fly; check, keys, compare
  void AddCheckAndCompare() {
    for (CLI::App* command : {plan, fly}) {
      command->add_option("--objective", objective,
                          "the trajectory's time allocation: min-time (default: as fast as the "
                          "vehicle's limits and margins allow) or snap (scaled to --max-speed and "
                          "--max-accel) ([trajectory] objective)");
      command->add_option("--max-speed", max_speed,
                          "the trajectory's speed limit [m/s] ([trajectory] max_speed)");
      command->add_option("--max-accel", max_accel,
                          "the trajectory's acceleration limit [m/s^2] ([trajectory] max_accel)");
    }
    fly->add_option("--telemetry-rate", fly_options.telemetry_rate,
                    "telemetry.csv rows per second [Hz] (default: every control step); must "
                    "divide the controller's rate");

    check = app.add_subcommand(
        "check", "validate a map or scenario and print a summary (exit 2 when it is bad)");
    AddInput(check);
    keys = app.add_subcommand(
        "keys",
        "print the reference of scenario keys: unit, default, range and meaning of each (Markdown; "
        "docs/scenario-keys.md)");

    compare = app.add_subcommand(
        "compare",
        "fly min-snap and the baselines (septic-full, quintic, cubic) on the same waypoints and "
        "times, print one table");
    compare->add_option("inputs", compare_inputs, "scenarios or maps")->capture_default_str();
    compare->add_option("--out", compare_out, "folder for the profile CSVs")->capture_default_str();
  }

  // sweep, sweep merge, sweep slurm; model
  void AddSweepCommands() {
    sweep = app.add_subcommand(
        "sweep",
        "fly every run of a sweep file (scenarios x grid x seeds), each in its own process; write "
        "results.jsonl and a report (see also: sweep merge, sweep slurm)");
    sweep->add_option("sweep", sweep_file, "sweep.toml");
    sweep->add_option("--out", sweep_options.out_dir,
                      "output folder (default: renders/<sweep name>/)");
    sweep->add_option("-j,--jobs", sweep_options.jobs,
                      "runs at once (default: SLURM_CPUS_PER_TASK, else the number of cores)");
    sweep->add_flag("--resume", sweep_options.resume,
                    "run only the runs that have no result in the output folder");
    sweep->add_option("--shard", shard_text,
                      "run the share i/N of the runs (run k belongs to shard k mod N); default: "
                      "from SLURM_ARRAY_TASK_ID, _MIN and _COUNT when set, else all");
    sweep->add_flag("--quiet", sweep_quiet, "no progress bar");
    sweep->add_flag(
        "--list", sweep_list,
        "print the runs (index, id, scenario, seed, grid values) and the shard's share, "
        "then stop: nothing runs or is written");
    merge =
        sweep->add_subcommand("merge", "join the results of a sweep's shards and write its report");
    merge->add_option("folders", merge_folders, "the shards' output folders")->required();
    merge->add_option("--out", merge_out,
                      "where the joined results go (default: the first folder)");
    slurm = sweep->add_subcommand(
        "slurm",
        "write an sbatch script that runs the sweep as a Slurm job array plus a merge job");
    slurm->add_option("sweep", sweep_file, "sweep.toml")->required();
    slurm->add_option("--array", slurm_options.array, "tasks in the job array")->required();
    slurm->add_option("--out", slurm_options.out_dir,
                      "folder for the script, the logs and the results (default: "
                      "<sweep name>.slurm/ beside the sweep file)");
    slurm->add_option("--partition", slurm_options.partition, "Slurm partition");
    slurm->add_option("--time", slurm_options.time, "time limit per task, e.g. 00:30:00");
    slurm->add_option("--cpus", slurm_options.cpus, "CPUs per task: runs each task flies at once")
        ->capture_default_str();
    slurm->add_flag("--submit", slurm_options.submit, "submit the array and the merge job");
    slurm->add_flag("--wait", slurm_options.wait, "with --submit: wait until the merge has run");

    forest = app.add_subcommand(
        "forest",
        "write a random forest map (Fast-Planner's benchmark: pillars over W x L, optional "
        "horizontal bars; start and goal at the two ends), as flightsim's JSON");
    forest->add_option("-o,--output", output, "output file (default: standard output)");
    forest->add_option("--size", forest_size, "W,L,H [m]: start to goal along x, across, height")
        ->capture_default_str();
    forest->add_option("--pillars", forest_params.pillars, "how many pillars")
        ->capture_default_str();
    forest->add_option("--width-min", forest_params.width_min, "a pillar's narrowest side [m]")
        ->capture_default_str();
    forest->add_option("--width-max", forest_params.width_max, "a pillar's widest side [m]")
        ->capture_default_str();
    forest->add_option("--bars", forest_params.bars, "horizontal bars (0.2 m thick, 2-4 m long)")
        ->capture_default_str();
    forest
        ->add_option("--clear-ends", forest_params.clear_ends,
                     "free ground at each end for the start and the goal [m]")
        ->capture_default_str();
    forest->add_option("--seed", forest_params.seed, "random seed")->capture_default_str();

    model = app.add_subcommand("model", "write the vehicle's MJCF model alone");
    model->add_option("-o,--output", output, "output file (default: standard output)");
  }

  // The command given, run; a scenario's commands through SetupFromOptions.
  int Dispatch(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
    if (model->parsed()) return RunModel(output, out);
    if (forest->parsed()) {
      forest_params.size = *ParsePointOption(forest_size, "--size");
      return RunForest(forest_params, output, out, err);
    }
    if (keys->parsed()) {
      out << ScenarioKeyReference();
      return 0;
    }
    if (compare->parsed()) return RunCompare(compare_inputs, compare_out, out, err);
    if (bench->parsed()) return RunBenchBinary(bench->remaining(), err);
    if (merge->parsed()) return RunSweepMerge(merge_folders, merge_out, out, err);
    if (slurm->parsed()) {
      if (slurm_options.wait && !slurm_options.submit) {
        throw InputError({"command line", 0}, "--wait", "needs --submit");
      }
      return RunSweepSlurm(ReadSweep(sweep_file), slurm_options, out, err);
    }
    if (sweep->parsed()) {
      if (sweep_file.empty()) {
        throw InputError({"command line", 0}, "sweep",
                         "expected a sweep file, or merge or slurm (aerobox sweep --help)");
      }
      if (!shard_text.empty()) sweep_options.shard = ParseShard(shard_text, "--shard");
      sweep_options.progress = !sweep_quiet;
      if (sweep_list) return ListSweep(ReadSweep(sweep_file), sweep_options, out);
      return RunSweep(ReadSweep(sweep_file), sweep_options, out, err);
    }
    if (fly->parsed()) {
      fly_options.out_dir = out_dir;
      fly_options.video = !no_video;
      fly_options.overview = !no_overview;
      fly_options.telemetry = !no_telemetry;
      fly_options.report = !no_report;
      fly_options.command = RepeatCommand(argc, argv);
      fly_options.progress = !quiet;
      char tail = 0;
      if (std::sscanf(size.c_str(), "%dx%d%c", &fly_options.width, &fly_options.height, &tail) !=
          2) {
        throw InputError({"command line", 0}, "--size", "expected WxH, e.g. 640x480");
      }
      ValidateFlyOptions(fly_options);
    }
    FlightSetup setup = SetupFromOptions();
    if (scene->parsed()) return RunScene(setup, output, out);
    if (plan->parsed()) return RunPlan(setup, out_dir, out, err);
    if (fly->parsed()) {
      // the seed in force, so that the command repeats the run
      if (!seed_given) fly_options.command += " --seed " + std::to_string(setup.seed);
      return RunFly(setup, fly_options, out, err);
    }
    return RunCheck(setup, out);
  }

  // The set-up the options name: the scenario or map, read with the overrides, then the
  // command line's own settings, each checked.
  // --start, --goal, --seed, --set, and the flags that are --set in other words.
  SetupOverrides Overrides() const {
    SetupOverrides overrides;
    overrides.start = ParsePointOption(start_text, "--start");
    for (size_t i = 0; i < goal_texts.size(); ++i) {
      const std::optional<Vec3> goal = ParsePointOption(goal_texts[i], "--goal");
      if (!goal) continue;
      if (i + 1 < goal_texts.size()) overrides.via.push_back(*goal);
      overrides.goal = goal;
    }
    if (seed_given) overrides.seed = seed;
    for (const std::string& text : set_texts) {
      overrides.settings.push_back(ParseSetting(text, "--set"));
    }
    // the flags that stand for scenario keys: --set with the flag's name in messages
    const auto flag = [&overrides](const char* option, const char* key, std::string value) {
      Setting setting;
      setting.key = key;
      setting.value = std::move(value);
      setting.where.file = "command line";
      setting.option = option;
      overrides.settings.push_back(std::move(setting));
    };
    if (BuiltInController()) {
      flag("--controller", "controller.kind", JsonQuoted(python_modules.controller));
    }
    if (!objective.empty()) flag("--objective", "trajectory.objective", JsonQuoted(objective));
    if (!max_speed.empty()) flag("--max-speed", "trajectory.max_speed", max_speed);
    if (!max_accel.empty()) flag("--max-accel", "trajectory.max_accel", max_accel);
    if (!trajectory_method.empty()) {
      flag("--trajectory", "trajectory.method", JsonQuoted(trajectory_method));
    }
    if (const std::optional<Vec3> wind = ParsePointOption(wind_text, "--wind", "m/s")) {
      flag("--wind", "wind.mean",
           "[" + FormatNumber(wind->x()) + ", " + FormatNumber(wind->y()) + ", " +
               FormatNumber(wind->z()) + "]");
    }
    if (!turbulence.empty()) {
      // one standard deviation on every axis; 0: none
      double sigma = 0.0;
      const bool some = ParseNumber(turbulence, &sigma) && sigma != 0.0;
      flag("--turbulence", "wind.turbulence", some ? "\"dryden\"" : "\"none\"");
      flag("--turbulence", "wind.intensity", turbulence);
    }
    return overrides;
  }

  // --controller names a registered controller (anything with a ':' is a Python class);
  // throws InputError for a name that is neither.
  bool BuiltInController() const {
    const std::string& name = python_modules.controller;
    if (name.empty() || name.find(':') != std::string::npos) return false;
    if (Controllers().Find(name) == nullptr) {
      throw InputError({"command line", 0}, "--controller",
                       "expected " + Controllers().NameList() + ", or file.py:Class");
    }
    return true;
  }

  FlightSetup SetupFromOptions() {
    const SetupOverrides overrides = Overrides();
    FlightSetup setup = LoadFlightSetup(input, overrides);
    ReadInjectedFaults(&setup);
    if (fly->parsed() && fly_options.telemetry_rate != 0) {
      // every controller's rate: the scenario's, or each vehicle's of several
      std::vector<std::pair<double, std::string>> rates = {{setup.controller.rate, ""}};
      if (!setup.vehicles.empty()) rates.clear();
      for (const SwarmMember& m : setup.vehicles) rates.push_back({m.controller.rate, m.name});
      for (const auto& [rate, vehicle] : rates) {
        const double every = rate / fly_options.telemetry_rate;
        if (!(fly_options.telemetry_rate > 0) || std::abs(every - std::round(every)) > 1e-9) {
          throw InputError({"command line", 0}, "--telemetry-rate",
                           "must divide the controller's rate" +
                               (vehicle.empty() ? std::string() : " of vehicle " + vehicle) + ", " +
                               FormatNumber(rate) + " Hz (e.g. 250, 50, 10)");
        }
      }
    }
    if (fly->parsed()) {
      if (BuiltInController()) python_modules.controller.clear();  // it was controller.kind
      UsePythonModules(python_modules, &setup);
    }
    return setup;
  }

  CLI::App app{"aerobox: a headless flight sandbox for a Tello-sized quadrotor in MuJoCo",
               "aerobox"};
  // the commands
  CLI::App* scene = nullptr;
  CLI::App* plan = nullptr;
  CLI::App* bench = nullptr;
  CLI::App* fly = nullptr;
  CLI::App* check = nullptr;
  CLI::App* keys = nullptr;
  CLI::App* compare = nullptr;
  CLI::App* sweep = nullptr;
  CLI::App* merge = nullptr;
  CLI::App* slurm = nullptr;
  CLI::App* model = nullptr;
  CLI::App* forest = nullptr;
  // their options' values
  std::string input;
  std::string start_text;
  std::vector<std::string> goal_texts;
  std::vector<std::string> set_texts;
  std::string output;
  std::string out_dir;
  std::uint64_t seed = 0;
  bool seed_given = false;
  bool no_video = false;
  bool no_overview = false, no_telemetry = false;
  bool no_report = false;
  FlyOptions fly_options;
  std::string size = "640x480";
  bool quiet = false;
  std::string trajectory_method;
  PythonModules python_modules;
  std::string wind_text;
  std::string turbulence;            // [m/s]; empty: the scenario's
  std::string max_speed, max_accel;  // [m/s], [m/s^2]; empty: the scenario's
  std::string objective;
  std::vector<std::string> compare_inputs = {
      "scenes/window/scenario.toml", "scenes/maze/scenario.toml", "scenes/forest/scenario.toml",
      "scenes/over_under/scenario.toml"};
  std::string compare_out = "renders/compare";
  std::string sweep_file, shard_text;
  SweepOptions sweep_options;
  bool sweep_quiet = false;
  bool sweep_list = false;
  std::vector<std::string> merge_folders;
  std::string merge_out;
  SlurmOptions slurm_options;
  ForestParams forest_params;
  std::string forest_size = FormatVector(ForestParams().size, ",");
};

}  // namespace

int RunCli(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  Cli cli;
  return cli.Run(argc, argv, out, err);
}

}  // namespace aerobox
