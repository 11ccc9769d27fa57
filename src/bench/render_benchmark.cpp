#include "bench/render_benchmark.h"

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <map>

#include "bench/benchmark_medians.h"
#include "render/renderer.h"
#include "render/video_encoder.h"
#include "scenario/scenario.h"

namespace aerobox {
namespace {

constexpr int kFrames = 60;

}  // namespace

void CompareVideoPath(const std::string& scenario, std::ostream& out, ProgressDisplay& progress,
                      const BenchSize& size) {
  const int frames = size.Count(kFrames, 4);
  const FlightSetup setup = LoadFlightSetup(scenario, {});
  const std::string xml = SceneMjcfFor(setup);
  const std::string video = (std::filesystem::temp_directory_path() /
                             ("aerobox-bench-" + std::to_string(::getpid()) + ".mp4"))
                                .string();
  struct Case {
    int width;
    int height;
    Quality quality;
    const char* name;
  };
  const Case cases[] = {{640, 480, Quality::kFast, "640x480 fast"},
                        {640, 480, Quality::kPretty, "640x480 pretty"},
                        {1280, 720, Quality::kFast, "1280x720 fast"},
                        {1280, 720, Quality::kPretty, "1280x720 pretty"}};
  for (const Case& c : cases) {
    // the vehicle moves along +y through the frames, seen by the chase camera
    const auto render = [xml, c, video, frames](benchmark::State& state, bool encode) {
      Simulation sim = Simulation::FromXml(xml, "bench");
      Renderer renderer(&sim, RenderSettings(c.width, c.height, c.quality));
      const State start = sim.VehicleState();
      Image image;
      for (auto _ : state) {
        state.PauseTiming();
        std::unique_ptr<VideoEncoder> encoder;
        if (encode) encoder = std::make_unique<VideoEncoder>(video, c.width, c.height, 30);
        state.ResumeTiming();
        for (int i = 0; i < frames; ++i) {
          State s = start;
          s.p_W.y() += 0.05 * i;
          sim.SetVehicleState(s);
          renderer.Render(CameraSpec{CameraKind::kChase, ""}, Overlay(), &image);
          if (encoder) encoder->AddFrame(image);
        }
        if (encoder) encoder->Finish();
      }
    };
    benchmark::RegisterBenchmark((std::string("bare/") + c.name).c_str(),
                                 [render](benchmark::State& s) { render(s, false); })
        ->Unit(benchmark::kSecond)
        ->Iterations(1)
        ->Repetitions(size.Repetitions(3))
        ->ReportAggregatesOnly(true);
    benchmark::RegisterBenchmark((std::string("video/") + c.name).c_str(),
                                 [render](benchmark::State& s) { render(s, true); })
        ->Unit(benchmark::kSecond)
        ->Iterations(1)
        ->Repetitions(size.Repetitions(3))
        ->ReportAggregatesOnly(true);
  }
  progress.Show("timing the video path ...", true);
  const std::map<std::string, double> medians = RunRegisteredBenchmarks();
  std::remove(video.c_str());
  progress.Clear();

  out << "| size, preset | render + read back [fps] | + H.264 encode [fps] | ratio |\n"
      << "|---|---|---|---|\n"
      << std::fixed;
  for (const Case& c : cases) {
    const double bare = frames / medians.at(std::string("bare/") + c.name);
    const double full = frames / medians.at(std::string("video/") + c.name);
    out << "| " << c.name << " | " << std::setprecision(1) << bare << " | " << full << " | "
        << std::setprecision(2) << full / bare << " |\n";
  }
}

}  // namespace aerobox
