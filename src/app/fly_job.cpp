#include "app/fly_job.h"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <future>
#include <iomanip>
#include <optional>
#include <sstream>

#include "app/exit_codes.h"
#include "app/files.h"
#include "common/number_format.h"
#include "mission/plan.h"
#include "mission/telemetry_table.h"
#include "planning/path_simplify.h"
#include "render/png.h"
#include "render/renderer.h"
#include "render/video_encoder.h"
#include "scene/scene_mjcf.h"
#include "telemetry/json_object.h"

namespace aerobox {
namespace fs = std::filesystem;
namespace {

std::atomic<bool> stop_requested{false};

constexpr double kCityRouteMargin = 25.0;  // [m] buildings kept in a city flight's scene
constexpr double kTreeIntro = 3.0;         // [s] of video in which the RRT* tree grows

struct Interrupted : std::runtime_error {
  Interrupted() : std::runtime_error("interrupted") {}
};

CameraSpec ParseCamera(const std::string& name) {
  if (name == "overview") return {CameraKind::kOverview, ""};
  if (name == "top") return {CameraKind::kTop, ""};
  return {CameraKind::kChase, ""};
}

std::string Hud(double t, const State& state, const char* status) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(1) << "t " << t << " s   speed " << state.v_W.norm()
       << " m/s   altitude " << state.p_W.z() << " m   " << status;
  return text.str();
}

}  // namespace

void RequestStop() { stop_requested = true; }

void ValidateFlyOptions(const FlyOptions& options) {
  const SourceLocation command_line{"command line", 0};
  if (options.quality != "fast" && options.quality != "pretty") {
    throw InputError(command_line, "--quality",
                     "expected fast or pretty, got '" + options.quality + "'");
  }
  if (options.camera != "chase" && options.camera != "overview" && options.camera != "top") {
    throw InputError(command_line, "--camera",
                     "expected chase, overview or top, got '" + options.camera + "'");
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

namespace {

int FlyInto(const std::string& folder, const FlightSetup& setup, const FlyOptions& options,
            std::ostream& out, std::ostream& err) {
  const auto file = [&folder](const char* name) { return (fs::path(folder) / name).string(); };

  ValidateFlyOptions(options);
  const QuadParams& vehicle = setup.vehicle;
  std::unique_ptr<Simulation> sim;
  std::unique_ptr<Renderer> renderer;
  const bool city = IsCityScale(setup.map);
  // the scene (with the boxes it keeps; the others are drawn as scenery) and its renderer
  const auto prepare = [&](const std::vector<bool>& keep_boxes) {
    RenderSettings render_settings(options.width, options.height,
                                   options.quality == "pretty" ? Quality::kPretty : Quality::kFast);
    // in a city the chase camera stays farther back, to show the streets around the vehicle
    if (city) render_settings.chase_distance = 6.0;
    for (size_t i = 0; i < keep_boxes.size(); ++i) {
      if (keep_boxes[i]) continue;
      const Box& box = setup.map.boxes[i];
      render_settings.scenery.push_back({box.extent.Center(), box.extent.HalfSize(), box.rgb});
    }
    sim = std::make_unique<Simulation>(
        Simulation::FromXml(SceneMjcfFor(setup, keep_boxes), setup.name + " (scene)"));
    try {
      renderer = std::make_unique<Renderer>(sim.get(), render_settings);
    } catch (const std::invalid_argument& e) {
      throw InputError({"command line", 0}, "--size", e.what());
    }
    renderer->ReleaseFromThread();
  };
  // A small map's scene does not depend on the plan, so it is made on a second thread while
  // the planner runs: loading the scene's textures into the GL context compiles llvmpipe's
  // shaders, which takes about as long as planning. A city's scene keeps only the buildings
  // near the route, so it waits for the plan.
  std::future<void> prepared;
  if (!city) prepared = std::async(std::launch::async, prepare, std::vector<bool>());

  // plan and solve; the preparation is waited for on every way out
  std::optional<PlanOutcome> planned;
  try {
    FlightSetup recorded = setup;
    recorded.planning.rrt.record_tree = options.show_tree;
    planned = PlanFlight(recorded);
  } catch (...) {
    if (prepared.valid()) prepared.wait();
    throw;
  }
  if (prepared.valid()) prepared.get();  // rethrows what the preparation threw
  const PlanOutcome& plan = *planned;
  JsonObject summary;
  summary.Add("scenario", setup.name).Add("seed", static_cast<long long>(setup.seed));
  const auto finish = [&](const char* status, int code) {
    summary.Add("status", status);
    JsonObject versions;
    versions.Add("aerobox", AEROBOX_VERSION).Add("mujoco", mj_versionString());
    summary.Add("versions", versions);
    WriteFileAtomically(file("summary.json"), summary.Text());
    return code;
  };
  summary.Add("planning_time_s", plan.result.stats.planning_time)
      .Add("planner_iterations", static_cast<long long>(plan.result.stats.iterations));
  if (plan.result.status != PlanStatus::kSolved) {
    out << "fly " << setup.name << ": " << ToString(plan.result.status) << "\n";
    return finish("no path", kExitNoPath);
  }
  WriteFileAtomically(file("path.csv"), PathCsv(plan.result.path));
  summary.Add("path_length_m", PathLength(plan.result.path));
  const TrajectoryResult& trajectory = *plan.trajectory;
  summary.Add("trajectory_time_s", trajectory.stats.solve_time)
      .Add("trajectory_duration_s", trajectory.stats.duration)
      .Add("trajectory_max_speed_mps", trajectory.stats.max_speed)
      .Add("trajectory_max_accel_mps2", trajectory.stats.max_accel);
  if (trajectory.status != TrajectoryStatus::kSolved) {
    out << "fly " << setup.name << ": no trajectory (" << trajectory.stats.solver_message << ")\n";
    return finish("no feasible trajectory", kExitNoTrajectory);
  }
  WriteFileAtomically(file("trajectory.csv"), TrajectoryCsv(trajectory.trajectory));
  if (city) {
    // MuJoCo 2.2 tests the vehicle against every geom of the world body at each step: 3845
    // buildings make a step 60 times dearer. The flight is lost (fly-away) once it is
    // flyaway_distance from its setpoint, so buildings farther than kCityRouteMargin from the
    // trajectory cannot be reached; they are drawn, not simulated. Clearance is still measured
    // against every box.
    static_assert(kCityRouteMargin > 10.0, "keep the margin far beyond the fly-away distance");
    std::vector<Vec3> route;
    for (double t = 0; t <= trajectory.trajectory.duration(); t += 0.1) {
      route.push_back(trajectory.trajectory.Evaluate3(t, kPosition));
    }
    route.push_back(trajectory.trajectory.Evaluate3(trajectory.trajectory.duration(), kPosition));
    route.push_back(VehicleRestPosition(setup.map, vehicle, setup.start));
    prepare(RouteBoxes(setup.map, route, kCityRouteMargin));
  }

  // fly: the vehicle rests at the start (on the floor when the start is at floor level)
  PlaceVehicleAtStart(setup.map, vehicle, setup.start, plan.start.used, sim.get());
  const CollisionWorld world(setup.map, CollisionParams{vehicle.collision_size, 0.0});
  // telemetry is streamed to telemetry.csv.partial as the vehicle flies, in blocks of rows, and
  // renamed when the flight is over
  StreamingFile telemetry_file(file("telemetry.csv"));
  const std::unique_ptr<Controller> controller = MakeController(setup.controller, vehicle);
  const std::vector<std::string> controller_columns = controller->ReportColumns();
  CsvTable telemetry = TelemetryTable(controller_columns);
  const size_t header_length = telemetry.Text().size();
  telemetry_file.Append(telemetry.Text());  // the header; blocks of rows follow

  // rendering: frames sampled on simulation time, encoded on a worker thread
  std::unique_ptr<VideoEncoder> video;
  const CameraSpec camera = ParseCamera(options.camera);
  Overlay overlay;
  overlay.path = plan.result.path;
  overlay.start = plan.start.used;
  overlay.goal = plan.goal.used;
  for (double t = 0; t <= trajectory.trajectory.duration(); t += 0.05) {
    overlay.trajectory.push_back(trajectory.trajectory.Evaluate(t, kPosition));
    overlay.speeds.push_back(trajectory.trajectory.Evaluate(t, kVelocity).norm());
  }
  if (options.video) {
    try {
      video = std::make_unique<VideoEncoder>(file("video.mp4"), options.width, options.height,
                                             options.fps);
    } catch (const std::runtime_error& e) {
      throw InputError({file("video.mp4"), 0}, "video", e.what());
    }
  }
  const bool show_progress = options.progress && isatty(STDERR_FILENO);
  const double frame_step = options.speed / options.fps;  // [s] of simulation per frame
  const double expected = trajectory.stats.duration;
  double next_frame = 0.0;
  int frames = 0;
  double next_png = 0.0;
  int png_frames = 0;
  const std::string frames_folder = file("frames");
  if (options.frames_every > 0) {
    std::error_code ec;
    fs::create_directories(frames_folder, ec);
    if (ec)
      throw InputError({frames_folder, 0}, "--frames-every", "cannot create: " + ec.message());
  }
  Image image;
  // --show-tree: the tree grows in the video's first seconds, seen from the overview camera,
  // as the planner added its edges; then it stays, and overview.png shows it whole
  overlay.tree = plan.result.tree;
  if (options.show_tree && overlay.tree.empty()) {
    err << "aerobox: --show-tree: no RRT* tree (the lattice planned this map)\n";
  }
  if (video && !overlay.tree.empty()) {
    Overlay growing = overlay;
    growing.path.clear();
    growing.trajectory.clear();
    growing.speeds.clear();
    const int intro = std::max(1, static_cast<int>(std::lround(kTreeIntro * options.fps)));
    for (int f = 1; f <= intro; ++f) {
      growing.tree_shown = overlay.tree.size() * f / intro;
      growing.text = "planning: RRT* tree, " + std::to_string(growing.tree_shown) + " edges";
      renderer->Render({CameraKind::kOverview, ""}, growing, &image);
      video->AddFrame(image);
      ++frames;
    }
  }
  overlay.tree_shown = overlay.tree.size();
  const auto begin = std::chrono::steady_clock::now();
  const auto on_sample = [&](const TelemetrySample& s) {
    if (stop_requested) throw Interrupted();
    AddTelemetryRow(s, &telemetry);
    if (telemetry.rows() >= 1000) {  // 4 s of flight a block
      telemetry_file.Append(telemetry.Text().substr(header_length));
      telemetry = TelemetryTable(controller_columns);
    }
    if (overlay.trail.empty() || (overlay.trail.back() - s.state.p_W).norm() > 0.02) {
      overlay.trail.push_back(s.state.p_W);
    }
    const bool png_due = options.frames_every > 0 && s.t + 1e-9 >= next_png;
    const bool video_due = video && s.t + 1e-9 >= next_frame;
    if (!png_due && !video_due) return;
    overlay.text = Hud(s.t, s.state, "flying");
    renderer->Render(camera, overlay, &image);
    if (png_due) {
      char name[32];
      std::snprintf(name, sizeof(name), "frame_%06d.png", png_frames++);
      WriteFileAtomically((fs::path(frames_folder) / name).string(), EncodePng(image));
      next_png += options.frames_every;
    }
    if (!video_due) return;
    next_frame += frame_step;
    video->AddFrame(image);
    ++frames;
    if (show_progress && frames % 10 == 0) {
      const double wall =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
      const double left = wall * std::max(0.0, expected - s.t) / std::max(s.t, 1e-9);
      err << "\rframe " << frames << "  " << std::fixed << std::setprecision(0)
          << frames / std::max(wall, 1e-9) << " fps  flight " << std::setprecision(1) << s.t
          << " / " << expected << " s  about " << std::setprecision(0) << left << " s left   "
          << std::flush;
    }
  };
  FlightResult flight;
  try {
    FlightLoop loop;
    loop.vehicle = &vehicle;
    loop.controller = controller.get();
    loop.control_rate = setup.controller.rate;
    loop.inner = setup.controller.inner;
    loop.clearance = [&world](const Vec3& p) { return world.Clearance(p); };
    loop.telemetry = on_sample;
    flight = FlyTrajectory(ReferenceOf(trajectory.trajectory), setup.flight, loop, sim.get());
  } catch (const Interrupted&) {
    if (show_progress) err << "\n";
    err << "aerobox: interrupted: no video, telemetry or summary written\n";
    return kExitInterrupted;  // the encoder's destructor removes its temporary file
  }
  if (show_progress) err << "\r" << std::string(60, ' ') << "\r" << std::flush;
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  if (video) video->Finish();

  // overview.png: the map, the path, the trajectory and the flown trail in one picture
  overlay.text = Hud(flight.time, sim->VehicleState(), ToString(flight.status));
  renderer->Render({CameraKind::kOverview, ""}, overlay, &image);
  WriteFileAtomically(file("overview.png"), EncodePng(image));
  telemetry_file.Append(telemetry.Text().substr(header_length));
  telemetry_file.Commit();

  summary.Add("flight_status", ToString(flight.status))
      .Add("flight_time_s", flight.time)
      .Add("flight_wall_time_s", wall)
      .Add("tracking_rms_m", flight.rms_error)
      .Add("tracking_max_m", flight.max_error)
      .Add("min_clearance_m", flight.min_clearance)
      .Add("collisions", flight.status == FlightStatus::kCollision ? 1 : 0)
      .Add("collision_with", flight.obstacle)
      .Add("telemetry_rate_hz", flight.control_rate)
      .Add("video_frames", frames)
      .Add("video_fps", options.fps);

  std::ostringstream table;
  table << std::fixed << std::setprecision(3);
  table << "fly " << setup.name << " (seed " << setup.seed << ")\n"
        << "  path        " << PathLength(plan.result.path) << " m, " << plan.result.path.size()
        << " waypoints, planned in " << plan.result.stats.planning_time << " s\n"
        << "  trajectory  " << trajectory.stats.duration << " s, max " << trajectory.stats.max_speed
        << " m/s, solved in " << trajectory.stats.solve_time << " s\n"
        << "  flight      " << ToString(flight.status) << " after " << flight.time << " s (" << wall
        << " s wall)";
  if (!flight.obstacle.empty()) table << ", hit " << flight.obstacle;
  table << "\n  tracking    RMS " << flight.rms_error << " m, max " << flight.max_error
        << " m; min clearance ";
  if (std::isfinite(flight.min_clearance)) {
    table << flight.min_clearance << " m\n";
  } else {
    table << "none (no obstacles)\n";
  }
  table << "  files       " << folder
        << "/{path,trajectory,telemetry}.csv, summary.json, overview.png"
        << (video ? ", video.mp4 (" + std::to_string(frames) + " frames)" : std::string()) << "\n";
  out << table.str();
  return finish(
      flight.status == FlightStatus::kReachedGoal ? "reached goal" : ToString(flight.status),
      flight.status == FlightStatus::kReachedGoal ? kExitReachedGoal : kExitFlightFailed);
}

}  // namespace

int RunFly(const FlightSetup& setup, const FlyOptions& options, std::ostream& out,
           std::ostream& err) {
  bool created = false;
  const std::string folder = PrepareOutputFolder(options.out_dir, setup.name, &created);
  try {
    return FlyInto(folder, setup, options, out, err);
  } catch (const InputError&) {
    // bad input leaves nothing behind: not even the folder this run made (if still empty)
    std::error_code ec;
    if (created && fs::is_empty(folder, ec)) fs::remove(folder, ec);
    throw;
  }
}

}  // namespace aerobox
