#include "outputs/flight_outputs.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>

#include "common/error.h"
#include "common/stop.h"
#include "mission/telemetry_table.h"
#include "outputs/files.h"
#include "perception/depth_camera.h"
#include "render/png.h"

namespace aerobox {
namespace fs = std::filesystem;
namespace {

constexpr double kTreeIntro = 3.0;        // [s] of video in which the RRT* tree grows
constexpr size_t kTelemetryBlock = 1000;  // rows (4 s of flight at 250 Hz) appended at once
constexpr float kUnseenAlpha = 0.2f;      // an unknown box before the sensor sees it

std::string Hud(double t, const State& state, double floor, const char* status,
                const std::optional<Vec3>& wind = std::nullopt) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(1) << "t " << t << " s  " << state.v_W.norm() << " m/s  "
       << state.p_W.z() - floor << " m above the floor  " << status;
  if (wind) text << "\nwind " << wind->norm() << " m/s (cyan arrow)";
  return text.str();
}

}  // namespace

CsvOutputs::CsvOutputs(std::string folder, int every, const TelemetryExtras& extras, bool telemetry)
    : folder_(std::move(folder)),
      every_(std::max(1, every)),
      extras_(extras),
      telemetry_(telemetry) {}
CsvOutputs::~CsvOutputs() = default;

void CsvOutputs::OnPlan(const PlanOutcome& plan) {
  if (plan.result.status != PlanStatus::kSolved) return;
  WriteFileAtomically((fs::path(folder_) / "path.csv").string(), PathCsv(plan.result.path));
  if (plan.trajectory->status != TrajectoryStatus::kSolved) return;
  WriteFileAtomically((fs::path(folder_) / "trajectory.csv").string(),
                      TrajectoryCsv(plan.trajectory->trajectory));
}

void CsvOutputs::OnFlightStart(const Simulation&, const Controller& controller) {
  if (!telemetry_) return;
  telemetry_file_ = std::make_unique<StreamingFile>((fs::path(folder_) / "telemetry.csv").string());
  schema_ = TelemetrySchema(controller, extras_);
  block_ = std::make_unique<CsvTable>(schema_.Table());
  header_length_ = block_->Text().size();
  telemetry_file_->Append(block_->Text());  // the header; blocks of rows follow
}

void CsvOutputs::OnSample(const TelemetrySample& sample) {
  if (!telemetry_) return;
  if (samples_++ % every_ != 0) return;
  schema_.AddRow(sample, block_.get());
  if (block_->rows() < kTelemetryBlock) return;
  telemetry_file_->Append(block_->Text().substr(header_length_));
  *block_ = schema_.Table();
}

void CsvOutputs::OnFlightEnd(const Simulation&, const FlightResult&) {
  if (!telemetry_) return;
  telemetry_file_->Append(block_->Text().substr(header_length_));
  telemetry_file_->Commit();
}

RenderOutputs::RenderOutputs(std::string folder, const FlightSetup& setup,
                             const RenderOptions& options, std::ostream& err)
    : folder_(std::move(folder)), setup_(setup), options_(options), err_(err) {}

void RenderOutputs::OnScene(Simulation& sim, const std::vector<bool>& kept) {
  RenderSettings settings(options_.width, options_.height, options_.quality);
  // in a city the chase camera stays farther back, to show the streets around the vehicle
  if (IsCityScale(setup_.map)) settings.chase_distance = 6.0;
  // the boxes the scene left out are drawn as scenery
  for (size_t i = 0; i < kept.size(); ++i) {
    if (kept[i]) continue;
    const Box& box = setup_.map.boxes[i];
    settings.scenery.push_back({box.extent.Center(), box.extent.HalfSize(), box.rgb});
  }
  try {
    renderer_ = std::make_unique<Renderer>(&sim, settings);
  } catch (const std::invalid_argument& e) {
    throw InputError({"command line", 0}, "--size", e.what());
  }
  // the first frames cost 0.45-0.6 s (llvmpipe compiles its shaders), the next ones 10 ms:
  // compiled here, while the planner works, they delay neither the flight's first step nor a
  // Ctrl-C there
  renderer_->CompileShaders();
  renderer_->ReleaseFromThread();  // the flight renders from the main thread
  // boxes the planner does not know: faint until the vehicle's sensor reveals them
  sim_ = &sim;
  unknown_geoms_.assign(setup_.map.boxes.size(), -1);
  for (size_t i = 0; i < setup_.unknown.size() && i < setup_.map.boxes.size(); ++i) {
    if (!setup_.unknown[i]) continue;
    const int id = mj_name2id(sim.model(), mjOBJ_GEOM, setup_.map.boxes[i].name.c_str());
    unknown_geoms_[i] = id;
    if (id >= 0) sim.mutable_model()->geom_rgba[4 * id + 3] = kUnseenAlpha;
  }
}

void RenderOutputs::OnDiscovery(const std::vector<double>& revealed_at,
                                const std::vector<ReplanEvent>& replans) {
  if (sim_ == nullptr) return;
  for (size_t i = 0; i < revealed_at.size() && i < unknown_geoms_.size(); ++i) {
    if (unknown_geoms_[i] >= 0 && revealed_at[i] >= 0) {
      sim_->mutable_model()->geom_rgba[4 * unknown_geoms_[i] + 3] = 1.0f;  // seen
    }
  }
  for (; replans_drawn_ < replans.size(); ++replans_drawn_) {
    const ReplanEvent& replan = replans[replans_drawn_];
    overlay_.abandoned.push_back(replan.abandoned);
    // the trajectory drawn is the one in force: up to where the replacement joins, then it
    if (!replan.replacement.empty() && !overlay_.trajectory.empty()) {
      size_t join = 0;
      double nearest = std::numeric_limits<double>::infinity();
      for (size_t i = 0; i < overlay_.trajectory.size(); ++i) {
        const double d = (overlay_.trajectory[i] - replan.replacement.front()).norm();
        if (d < nearest) {
          nearest = d;
          join = i;
        }
      }
      overlay_.trajectory.resize(join);
      overlay_.speeds.resize(join);
      overlay_.trajectory.insert(overlay_.trajectory.end(), replan.replacement.begin(),
                                 replan.replacement.end());
      overlay_.speeds.insert(overlay_.speeds.end(), replan.replacement_speeds.begin(),
                             replan.replacement_speeds.end());
    }
  }
}

Image ColourDepth(const DepthImage& image, double range) {
  Image out;
  out.width = image.width;
  out.height = image.height;
  out.rgb.assign(static_cast<size_t>(3 * image.width * image.height), 0);
  const std::uint8_t near[3] = {255, 220, 60}, far[3] = {40, 10, 60};
  for (int v = 0; v < image.height; ++v) {
    for (int u = 0; u < image.width; ++u) {
      const float depth = image.depth[static_cast<size_t>(v * image.width + u)];
      if (!(depth > 0.0f)) continue;
      const double t = std::clamp(depth / range, 0.0, 1.0);
      std::uint8_t* px = out.Pixel(u, v);
      for (int c = 0; c < 3; ++c)
        px[c] = static_cast<std::uint8_t>(near[c] + t * (far[c] - near[c]));
    }
  }
  return out;
}

void DrawInset(const Image& inset, Image* frame) {
  if (inset.width <= 0 || frame->width < 16) return;
  const int width = frame->width / 4;
  const int height = std::max(1, width * inset.height / inset.width);
  const int x0 = frame->width - width - 8, y0 = 8;
  if (x0 < 1 || y0 + height + 1 > frame->height) return;
  for (int y = -1; y <= height; ++y) {
    for (int x = -1; x <= width; ++x) {
      std::uint8_t* px = frame->Pixel(x0 + x, y0 + y);
      if (x < 0 || y < 0 || x == width || y == height) {
        px[0] = px[1] = px[2] = 255;
        continue;
      }
      const std::uint8_t* from = inset.Pixel(x * inset.width / width, y * inset.height / height);
      std::copy(from, from + 3, px);
    }
  }
}

void RenderOutputs::OnDepthFrame(double, const DepthImage& image, const OccupancyGrid&) {
  // coloured only when a frame shows it: most depth frames are never drawn
  depth_frame_ = image;
  inset_stale_ = true;
}

void RenderOutputs::OnPlan(const PlanOutcome& plan) {
  overlay_.path = plan.result.path;
  overlay_.start = plan.start.used;
  overlay_.goal = plan.goal.used;
  overlay_.via.clear();
  for (const Endpoint& goal : plan.via) overlay_.via.push_back(goal.used);
  overlay_.tree = plan.result.tree;
  if (!plan.trajectory || plan.trajectory->status != TrajectoryStatus::kSolved) return;
  const PiecewiseTrajectory& trajectory = plan.trajectory->trajectory;
  for (double t = 0; t <= trajectory.duration(); t += 0.05) {
    overlay_.trajectory.push_back(trajectory.Evaluate(t, kPosition));
    overlay_.speeds.push_back(trajectory.Evaluate(t, kVelocity).norm());
  }
}

void RenderOutputs::Frame(const std::string& text, const CameraSpec& camera,
                          const Overlay& overlay) {
  ThrowIfStopRequested("rendering the video");
  Overlay shown = overlay;
  shown.text = text;
  renderer_->Render(camera, shown, &image_);
}

void RenderOutputs::OnFlightStart(const Simulation&, const Controller&) {
  if (options_.video) {
    const std::string path = (fs::path(folder_) / "video.mp4").string();
    try {
      video_ = std::make_unique<VideoEncoder>(path, options_.width, options_.height, options_.fps);
    } catch (const std::runtime_error& e) {
      throw InputError({path, 0}, "video", e.what());
    }
  }
  if (options_.frames_every > 0) {
    const fs::path frames = fs::path(folder_) / "frames";
    std::error_code ec;
    fs::create_directories(frames, ec);
    if (ec)
      throw InputError({frames.string(), 0}, "--frames-every", "cannot create: " + ec.message());
  }
  // --show-tree: the tree grows in the video's first seconds, seen from the overview camera,
  // as the planner added its edges; then it stays, and overview.png shows it whole
  if (options_.show_tree && overlay_.tree.empty()) {
    err_ << "aerobox: --show-tree: no RRT* tree (the lattice planned this map)\n";
  }
  if (video_ && !overlay_.tree.empty()) {
    Overlay growing = overlay_;
    growing.path.clear();
    growing.trajectory.clear();
    growing.speeds.clear();
    const int intro = std::max(1, static_cast<int>(std::lround(kTreeIntro * options_.fps)));
    for (int f = 1; f <= intro; ++f) {
      growing.tree_shown = overlay_.tree.size() * f / intro;
      Frame("planning: RRT* tree, " + std::to_string(growing.tree_shown) + " edges",
            {CameraKind::kOverview, ""}, growing);
      video_->AddFrame(image_);
      ++frames_;
    }
  }
  overlay_.tree_shown = overlay_.tree.size();
}

void RenderOutputs::OnSample(const TelemetrySample& s) {
  if (overlay_.trail.empty() || (overlay_.trail.back() - s.state.p_W).norm() > 0.02) {
    overlay_.trail.push_back(s.state.p_W);
  }
  // frames are sampled on simulation time
  const bool png_due = options_.frames_every > 0 && s.t + 1e-9 >= next_png_;
  const bool video_due = video_ && s.t + 1e-9 >= next_frame_;
  if (!png_due && !video_due) return;
  if (setup_.wind.Enabled()) {
    overlay_.wind_W = s.wind_W;
    overlay_.wind_origin = s.state.p_W + Vec3(0, 0, 0.15);  // above the vehicle
  }
  // from a camera that sees the whole map, the vehicle is a pixel or two: marked
  const bool far =
      options_.camera.kind == CameraKind::kOverview || options_.camera.kind == CameraKind::kTop;
  overlay_.vehicle = far ? std::optional<Vec3>(s.state.p_W) : std::nullopt;
  overlay_.others.clear();
  for (int i = 1; far && i < sim_->vehicle_count(); ++i) {
    overlay_.others.push_back(sim_->vehicle(i).VehicleState().p_W);
  }
  Frame(Hud(s.t, s.state, setup_.map.bounds.min.z(), "flying", overlay_.wind_W), options_.camera,
        overlay_);
  if (inset_stale_) depth_inset_ = ColourDepth(depth_frame_, setup_.sensing.range);
  inset_stale_ = false;
  DrawInset(depth_inset_, &image_);
  overlay_.vehicle.reset();
  overlay_.others.clear();
  if (png_due) {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%06d.png", png_frames_++);
    WriteFileAtomically((fs::path(folder_) / "frames" / name).string(), EncodePng(image_));
    next_png_ += options_.frames_every;
  }
  if (!video_due) return;
  next_frame_ += options_.speed / options_.fps;  // [s] of simulation per frame
  video_->AddFrame(image_);
  ++frames_;
}

void RenderOutputs::OnFlightEnd(const Simulation& sim, const FlightResult& result) {
  if (video_) video_->Finish();
  if (!options_.overview) return;
  // overview.png: the map, the path, the trajectory and the flown trail in one picture, with
  // the map from above in a corner and what the lines mean
  Overlay overview = overlay_;
  overview.top_inset = true;
  overview.legend =
      std::string(
          "yellow: path   blue-red: trajectory, slow-fast\n"
          "black: flown   green: start   red: goal   inset: from above") +
      (setup_.HasUnknown() ? "\nfaint: never seen   grey: paths given up when replanning" : "");
  if (result.status == FlightStatus::kCollision) {
    overview.collision = result.end_position;
    overview.legend += "\nmagenta: where it hit " + result.obstacle;
  }
  Frame(Hud(result.time, sim.VehicleState(), setup_.map.bounds.min.z(), ToString(result.status)),
        {CameraKind::kOverview, ""}, overview);
  WriteFileAtomically((fs::path(folder_) / "overview.png").string(), EncodePng(image_));
}

void PhaseLines::OnPlan(const PlanOutcome& plan) {
  if (plan.trajectory) duration_ = plan.trajectory->stats.duration;
}

void PhaseLines::OnFlightStart(const Simulation&, const Controller&) {
  err_ << name_ << ": flying, " << std::fixed << std::setprecision(2) << duration_
       << " s of trajectory\n"
       << std::defaultfloat << std::flush;
}

void ProgressLine::OnPlan(const PlanOutcome& plan) {
  if (plan.trajectory) expected_ = plan.trajectory->stats.duration;
  begin_ = std::chrono::steady_clock::now();
}

void ProgressLine::OnSample(const TelemetrySample& s) {
  const int frames = frames_->video_frames();
  if (frames < shown_ + 10) return;
  shown_ = frames;
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin_).count();
  const double left = wall * std::max(0.0, expected_ - s.t) / std::max(s.t, 1e-9);
  std::ostringstream line;
  line << "frame " << frames << "  " << std::fixed << std::setprecision(0)
       << frames / std::max(wall, 1e-9) << " fps  flight " << std::setprecision(1) << s.t << " / "
       << expected_ << " s  about " << std::setprecision(0) << left << " s left";
  display_.Show(line.str());
}

}  // namespace aerobox
