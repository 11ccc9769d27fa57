#include "app/fly_job.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "app/exit_codes.h"
#include "app/swarm_job.h"
#include "common/number_format.h"
#include "mission/mission.h"
#include "outputs/files.h"
#include "outputs/flight_outputs.h"
#include "outputs/interrupt.h"
#include "outputs/report.h"
#include "outputs/summary.h"
#include "planning/path_simplify.h"
#include "render/video_encoder.h"
#include "scene/scene_mjcf.h"
#include "telemetry/json_object.h"

namespace aerobox {
namespace fs = std::filesystem;
void ValidateFlyOptions(const FlyOptions& options) {
  const SourceLocation command_line{"command line", 0};
  if (options.quality != "fast" && options.quality != "pretty") {
    throw InputError(command_line, "--quality",
                     "expected fast or pretty, got '" + options.quality + "'");
  }
  try {
    ParseCamera(options.camera);
  } catch (const std::invalid_argument& e) {
    throw InputError(command_line, "--camera", e.what());
  }
  if (!(options.fps > 0 && options.fps <= 240)) {
    throw InputError(command_line, "--fps", "expected 1 to 240 frames per second");
  }
  if (!(options.speed > 0 && options.speed <= 100)) {
    throw InputError(command_line, "--speed", "expected a playback speed above 0, at most 100");
  }
  if (!(options.frames_every >= 0 && std::isfinite(options.frames_every))) {
    throw InputError(command_line, "--frames-every", "expected seconds >= 0");
  }
  // every scene has a 1920 x 1080 off-screen buffer (SceneOptions); H.264 in yuv420p needs
  // even sides
  const SceneOptions scene;
  if (options.width < 16 || options.height < 16 || options.width > scene.offscreen_width ||
      options.height > scene.offscreen_height) {
    throw InputError(command_line, "--size",
                     std::to_string(options.width) + "x" + std::to_string(options.height) +
                         " is outside 16x16 .. " + std::to_string(scene.offscreen_width) + "x" +
                         std::to_string(scene.offscreen_height));
  }
  if (options.video && (options.width % 2 != 0 || options.height % 2 != 0)) {
    throw InputError(command_line, "--size",
                     std::to_string(options.width) + "x" + std::to_string(options.height) +
                         ": a video needs even sides (H.264, yuv420p)");
  }
}

RenderOptions RenderOptionsFor(const FlyOptions& options) {
  RenderOptions render;
  render.width = options.width;
  render.height = options.height;
  render.quality = options.quality == "pretty" ? Quality::kPretty : Quality::kFast;
  render.camera = ParseCamera(options.camera);
  render.video = options.video;
  render.overview = options.overview;
  render.fps = options.fps;
  render.speed = options.speed;
  render.frames_every = options.frames_every;
  render.show_tree = options.show_tree;
  return render;
}

int TelemetryEvery(const FlyOptions& options, double rate) {
  return options.telemetry_rate > 0 ? static_cast<int>(std::lround(rate / options.telemetry_rate))
                                    : 1;
}

std::string ReportCommand(const FlyOptions& options, const FlightSetup& setup) {
  if (!options.command.empty()) return options.command;
  return "aerobox fly " + setup.map.source + " --seed " + std::to_string(setup.seed);
}

namespace {

// A run's outputs in its staging folder, each an observer of the run.
struct FlyOutputs {
  FlyOutputs(const std::string& folder, const FlightSetup& setup, const FlyOptions& options,
             std::ostream& err)
      : every(TelemetryEvery(options, setup.controller.rate)),
        csv(folder, every, TelemetryExtrasFor(setup), options.telemetry) {
    parts.observers = {&csv};
    // no pictures asked for: no renderer either (a sweep's runs save its set-up)
    if (options.video || options.overview || options.frames_every > 0) {
      pictures.emplace(folder, setup, RenderOptionsFor(options), err);
      parts.observers.push_back(&*pictures);
    }
    if (options.report) {
      report.emplace(folder, setup);
      parts.observers.push_back(&*report);
    }
    if (options.progress) {
      phases.emplace("fly " + setup.name, err);
      parts.observers.push_back(&*phases);
    }
    if (options.video && options.progress && isatty(STDERR_FILENO)) {
      progress.emplace(&*pictures, err);
      parts.observers.push_back(&*progress);
    }
  }
  int video_frames() const { return pictures ? pictures->video_frames() : 0; }

  int every;  // control steps per telemetry row
  CsvOutputs csv;
  std::optional<RenderOutputs> pictures;
  std::optional<ReportOutputs> report;
  std::optional<PhaseLines> phases;
  std::optional<ProgressLine> progress;
  MissionParts parts;
};

void WarnBeforeFlight(const FlightSetup& setup, std::ostream& err) {
  if (const std::string warning = LimitsWarning(setup); !warning.empty()) {
    err << "aerobox: warning: " << warning << "\n";
  }
  if (setup.HasUnknown() && setup.sensing.kind != SensingParams::Kind::kOmni &&
      !setup.flight.face_travel) {
    err << "aerobox: warning: the depth camera looks along the body's x axis and the yaw is "
           "held ([flight] yaw = \"hold\"): flying any other way, it sees sideways; yaw = "
           "\"travel\" turns it along the travel\n";
  }
}

// The user's controller failed: bad input, as a file that does not import is (exit 2, the
// folder as it was); its traceback first, as Python prints one, then the message.
void ThrowIfControllerFailed(const FlightSetup& setup, const MissionResult& result,
                             std::ostream& err) {
  if (!result.flown || result.flight.status != FlightStatus::kControllerFailed) return;
  const std::string& kind = setup.controller.kind;
  const bool python = kind.find(':') != std::string::npos;
  if (!result.flight.detail.empty()) err << result.flight.detail << "\n";
  throw InputError({python ? kind.substr(0, kind.rfind(':')) : "", 0},
                   python ? "--controller" : "controller.kind", result.flight.message);
}

// The table's lines of the path, the trajectory and the flight.
void PlanAndFlightLines(const FlightSetup& setup, const MissionResult& result,
                        std::ostream& table) {
  const PlanOutcome& plan = result.plan;
  const TrajectoryResult& trajectory = *plan.trajectory;
  const FlightResult& flight = result.flight;
  table << "fly " << setup.name << " (seed " << setup.seed << ")\n"
        << DescribeMoves(plan.start, plan.goal) << "  path        " << PathLength(plan.result.path)
        << " m, " << plan.result.path.size() << " waypoints, planned in "
        << plan.result.stats.planning_time << " s"
        << (plan.result.stats.time_capped
                ? " (cut by [planner] time_budget: this path depends on the machine's speed, not "
                  "the seed alone)"
                : "")
        << "\n"
        << "  trajectory  " << trajectory.stats.duration << " s, max " << trajectory.stats.max_speed
        << " m/s, solved in " << trajectory.stats.solve_time << " s"
        << (trajectory.stats.binding_limit.limit.empty()
                ? std::string()
                : " (" + trajectory.stats.binding_limit.limit + " at " +
                      FormatNumber(std::round(trajectory.stats.binding_limit.ratio * 100)) +
                      " % of its limit)")
        << (trajectory.stats.closed_form_fallback
                ? " (" + trajectory.stats.solver_message +
                      "; the closed form flown instead passed the same checks: nothing to do)"
                : std::string())
        << "\n"
        << "  flight      " << ToString(flight.status) << " after " << flight.time << " s ("
        << (flight.takeoff_time > 0 ? FormatNumber(std::round(flight.takeoff_time * 100) / 100) +
                                          " s of it lifting off the floor, "
                                    : std::string())
        << result.flight_wall_time << " s wall)";
  if (!flight.obstacle.empty()) table << ", hit " << flight.obstacle;
  if (!flight.message.empty()) table << ": " << flight.message;
}

// A mission's line: each goal and when it was reached.
void GoalsLine(const FlightSetup& setup, const MissionResult& result, std::ostream& table) {
  const FlightResult& flight = result.flight;
  const size_t goals = result.plan.via.size() + 1;
  const size_t reached =
      flight.goal_times.size() + (flight.status == FlightStatus::kReachedGoal ? 1 : 0);
  table << "\n  goals       " << reached << " of " << goals << " reached";
  for (size_t i = 0; i < goals; ++i) {
    table << (i == 0 ? ": " : ", ") << i + 1 << " ";
    if (i < flight.goal_times.size()) {
      table << "at " << flight.goal_times[i] << " s";
    } else if (i + 1 == goals && flight.status == FlightStatus::kReachedGoal) {
      table << "at " << flight.time << " s";
    } else {
      table << "not reached";
    }
  }
  if (setup.stop_at_goals) table << " (stopping at each)";
}

void DiscoveryLine(const MissionResult& result, std::ostream& table) {
  table << "\n  discovery   " << result.revealed_boxes << " of " << result.unknown_boxes
        << " unknown boxes revealed; " << result.replans.size() << " replan(s)";
  constexpr size_t kListed = 5;  // the rest are in summary.json
  for (size_t i = 0; i < result.replans.size(); ++i) {
    const ReplanEvent& e = result.replans[i];
    if (i == kListed) {
      table << "; " << result.replans.size() - kListed << " more in summary.json";
      break;
    }
    table << "; at " << e.t << " s (" << e.trigger << "): " << e.outcome << " in "
          << std::setprecision(1) << 1e3 * e.latency << " ms" << std::setprecision(4);
    if (e.time_capped) {
      table << " (cut by [replan] time_budget: not reproducible by seed)";
    }
  }
  if (result.occupancy) {
    const OccupancyGrid& grid = *result.occupancy->grid;
    table << "\n  map         " << grid.occupied_count() << " occupied and " << grid.free_count()
          << " free cells of " << grid.cell_count() << " (" << grid.resolution() << " m), from "
          << result.occupancy->cost.frames << " depth frames";
  }
}

void SpeedAndTrackingLines(const FlightResult& flight, std::ostream& table) {
  // tracking errors of a millimetre or less: three significant digits, not "0.000 m"
  const auto metres = [](double value) {
    std::ostringstream text;
    text << std::setprecision(3) << value << " m";
    return text.str();
  };
  table << "\n  speed       " << std::setprecision(2) << flight.AverageSpeed()
        << " m/s on average, " << flight.top_speed << " m/s at most; rotors at most "
        << std::setprecision(0) << 100 * flight.peak_rotor_fraction
        << " % of their limit, saturated " << std::setprecision(2) << flight.saturated_time << " s"
        << std::setprecision(3);
  table << "\n  tracking    RMS " << metres(flight.rms_error) << ", max "
        << metres(flight.max_error) << "; min clearance ";
  if (std::isfinite(flight.min_clearance)) {
    table << metres(flight.min_clearance) << "\n";
  } else {
    table << "none (no obstacles)\n";
  }
}

// The table a flown run prints.
std::string FlightTable(const OutputFolder& output, const FlightSetup& setup,
                        const FlyOptions& options, const MissionResult& result, int video_frames) {
  std::ostringstream table;
  table << std::fixed << std::setprecision(3);
  PlanAndFlightLines(setup, result, table);
  if (!result.plan.via.empty()) GoalsLine(setup, result, table);
  if (setup.HasUnknown()) DiscoveryLine(result, table);
  SpeedAndTrackingLines(result.flight, table);
  table << "  files       " << output.path()
        << (options.telemetry ? "/{path,trajectory,telemetry}.csv" : "/{path,trajectory}.csv")
        << ", summary.json" << (options.overview ? ", overview.png" : "")
        << (options.report ? ", report.html" : "")
        << (options.video ? ", video.mp4 (" + std::to_string(video_frames) + " frames)"
                          : std::string())
        << "\n";
  // a flight that reached the goal far from its trajectory did not fly the trajectory
  if (const std::string note = TrackingNote(setup, result.flight); !note.empty()) {
    table << "  warning     " << note << "\n";
  }
  return table.str();
}

// summary.json, then report.html (a page that cannot be made is a warning: the flight's own
// files are written).
void WriteSummaryAndReport(const std::string& folder, const FlightSetup& setup,
                           const FlyOptions& options, const MissionResult& result,
                           const FlyOutputs& outputs, std::ostream& err) {
  const JsonObject summary =
      RunSummary(setup, result, {outputs.every, outputs.video_frames(), options.fps});
  WriteFileAtomically((fs::path(folder) / "summary.json").string(), summary.Text());
  if (!outputs.report) return;
  try {
    outputs.report->Write(summary.Text(), ReportCommand(options, setup));
  } catch (const InputError& e) {
    err << "aerobox: warning: no report.html: " << e.what() << "\n";
  }
}

// Flies and writes the outputs into `output`'s staging folder; RunFly commits them.
int FlyInto(const OutputFolder& output, const FlightSetup& setup, const FlyOptions& options,
            std::ostream& out, std::ostream& err) {
  ValidateFlyOptions(options);
  if (!setup.vehicles.empty()) return FlySwarmInto(output, setup, options, out, err);
  FlyOutputs outputs(output.staging(), setup, options, err);
  WarnBeforeFlight(setup, err);
  FlightSetup recorded = setup;
  recorded.planning.rrt.record_tree = options.show_tree;
  if (options.progress) err << "fly " << setup.name << ": planning\n";
  const MissionResult result = RunMission(recorded, outputs.parts);
  outputs.progress.reset();
  ThrowIfControllerFailed(setup, result, err);

  const PlanOutcome& plan = result.plan;
  int code = kExitFlightFailed;
  if (result.status == MissionStatus::kNoPath) {
    out << DescribeMoves(plan.start, plan.goal) << "fly " << setup.name << ": "
        << ToString(plan.result.status) << "\n";
    if (plan.result.status == PlanStatus::kPathBlocked) {
      out << "  " << DescribeBlockedPath(plan) << "\n";
    }
    code = kExitNoPath;
  } else if (result.status == MissionStatus::kNoTrajectory) {
    out << "fly " << setup.name << ": no trajectory (" << plan.trajectory->stats.solver_message
        << ")\n";
    code = kExitNoTrajectory;
  } else {
    out << FlightTable(output, setup, options, result, outputs.video_frames());
    if (result.status == MissionStatus::kReachedGoal) code = kExitReachedGoal;
  }
  WriteSummaryAndReport(output.staging(), setup, options, result, outputs, err);
  return code;
}

}  // namespace

int RunFly(const FlightSetup& setup, const FlyOptions& options, std::ostream& out,
           std::ostream& err) {
  // the folder keeps its earlier run until this one has ended (an exception, Ctrl-C included,
  // leaves it untouched)
  OutputFolder folder(options.out_dir, setup.name);
  const int code = folder.Run([&] { return FlyInto(folder, setup, options, out, err); });
  folder.Commit();
  return code;
}

}  // namespace aerobox
