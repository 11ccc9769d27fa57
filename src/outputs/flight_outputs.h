// The observers of `aerobox fly` (mission/mission.h): each writes or shows one kind of output.
#pragma once

#include <chrono>
#include <memory>
#include <ostream>
#include <string>

#include "common/progress.h"
#include "mission/mission.h"
#include "mission/telemetry_table.h"
#include "render/renderer.h"
#include "render/video_encoder.h"
#include "telemetry/csv_table.h"

namespace aerobox {

class StreamingFile;

// path.csv and trajectory.csv once planned; telemetry.csv streamed during the flight (in blocks
// of rows, under a temporary name, renamed when the flight is over).
class CsvOutputs : public MissionObserver {
 public:
  // `every`: one telemetry row per this many control steps
  // `extras`: the columns of the flight's wind and sensors (TelemetryExtrasFor)
  // `telemetry`: false writes path.csv and trajectory.csv only
  explicit CsvOutputs(std::string folder, int every = 1, const TelemetryExtras& extras = {},
                      bool telemetry = true);
  ~CsvOutputs() override;
  void OnPlan(const PlanOutcome& plan) override;
  void OnFlightStart(const Simulation&, const Controller& controller) override;
  void OnSample(const TelemetrySample& sample) override;
  void OnFlightEnd(const Simulation&, const FlightResult&) override;

 private:
  std::string folder_;
  int every_;
  TelemetryExtras extras_;
  bool telemetry_;
  long samples_ = 0;
  std::unique_ptr<StreamingFile> telemetry_file_;
  TelemetrySchema schema_;  // the flying controller's, from OnFlightStart
  std::unique_ptr<CsvTable> block_;
  size_t header_length_ = 0;
};

struct RenderOptions {
  int width = 640;  // [pixels]
  int height = 480;
  Quality quality = Quality::kFast;
  CameraSpec camera;
  bool video = true;          // video.mp4
  bool overview = true;       // overview.png
  int fps = 30;               // video frames per second
  double speed = 1.0;         // playback speed
  double frames_every = 0.0;  // [s] between frames/*.png (0: none)
  bool show_tree = false;     // the RRT* tree's growth opens the video
};

// A depth image coloured by depth: near yellow, at `range` [m] dark purple, no return black.
Image ColourDepth(const DepthImage& image, double range);
// `inset` scaled (nearest pixel) to a quarter of `frame`'s width, in its top right corner, with
// a white frame.
void DrawInset(const Image& inset, Image* frame);

// video.mp4, frames/*.png and overview.png, from a renderer made as soon as the scene exists.
class RenderOutputs : public MissionObserver {
 public:
  RenderOutputs(std::string folder, const FlightSetup& setup, const RenderOptions& options,
                std::ostream& err);
  void OnScene(Simulation& sim, const std::vector<bool>& kept) override;
  void OnPlan(const PlanOutcome& plan) override;
  void OnFlightStart(const Simulation&, const Controller&) override;
  void OnSample(const TelemetrySample& sample) override;
  void OnFlightEnd(const Simulation& sim, const FlightResult& result) override;
  // unknown boxes drawn faint until revealed; the paths replanning gave up, in grey
  void OnDiscovery(const std::vector<double>& revealed_at,
                   const std::vector<ReplanEvent>& replans) override;
  // a depth camera's last frame, drawn in the frames' top right corner
  void OnDepthFrame(double t, const DepthImage& image, const OccupancyGrid& map) override;

  int video_frames() const { return frames_; }

 private:
  void Frame(const std::string& text, const CameraSpec& camera, const Overlay& overlay);

  std::string folder_;
  const FlightSetup& setup_;
  RenderOptions options_;
  std::ostream& err_;
  std::unique_ptr<Renderer> renderer_;
  std::unique_ptr<VideoEncoder> video_;
  Overlay overlay_;
  Image image_;
  double next_frame_ = 0.0;
  double next_png_ = 0.0;
  int frames_ = 0;
  int png_frames_ = 0;
  Simulation* sim_ = nullptr;
  std::vector<int> unknown_geoms_;  // the scene's geom of each unknown box (-1: not in it)
  DepthImage depth_frame_;          // the depth camera's last frame
  Image depth_inset_;               // ... coloured (empty: none)
  bool inset_stale_ = false;        // depth_inset_ is not yet depth_frame_'s
  size_t replans_drawn_ = 0;
};

// A line on the error stream as the flight begins ("fly window: flying, 7.40 s of trajectory"),
// after the command's own "planning" line: a log, or a script, sees where the run is.
class PhaseLines : public MissionObserver {
 public:
  PhaseLines(std::string name, std::ostream& err) : name_(std::move(name)), err_(err) {}
  void OnPlan(const PlanOutcome& plan) override;
  void OnFlightStart(const Simulation&, const Controller&) override;

 private:
  std::string name_;
  std::ostream& err_;
  double duration_ = 0.0;  // [s] of trajectory
};

// A progress line on a terminal: frames, frames per second, flight time and time left.
class ProgressLine : public MissionObserver {
 public:
  ProgressLine(const RenderOutputs* frames, std::ostream& err)
      : frames_(frames), display_(err, true, 0.0) {}
  void OnPlan(const PlanOutcome& plan) override;
  void OnSample(const TelemetrySample& sample) override;

 private:
  const RenderOutputs* frames_;
  ProgressDisplay display_;
  double expected_ = 0.0;  // [s] of flight
  int shown_ = 0;          // frames when the line was last written
  std::chrono::steady_clock::time_point begin_;
};

}  // namespace aerobox
