#include <doctest/doctest.h>

extern "C" {
#include <libavformat/avformat.h>
}

#include <cmath>
#include <filesystem>
#include <fstream>

#include "render/png.h"
#include "render/renderer.h"
#include "render/video_encoder.h"
#include "scene/scene_mjcf.h"
#include "test_support.h"
#include "vehicle/model_names.h"

namespace aerobox {
namespace {

Simulation SmallScene(const Vec3& vehicle) {
  Map map;
  map.name = "small";
  map.bounds = {Vec3(0, 0, 0), Vec3(4, 4, 2)};
  map.boxes.push_back({{Vec3(2.5, 2.5, 0), Vec3(3, 3, 1.5)}, Vec3(0.8, 0.1, 0.1), "block_0", 1});
  SceneOptions options;
  options.vehicle_position = vehicle;
  return Simulation::FromXml(BuildSceneMjcf(map, QuadParams(), options), "small");
}

// Where the camera sees a world point: pixel column and row (top-down), from the camera's pose
// in mjData and its vertical field of view.
Eigen::Vector2d Project(const Simulation& sim, const char* camera, const Vec3& p, int w, int h) {
  const int id = mj_name2id(sim.model(), mjOBJ_CAMERA, camera);
  const Vec3 eye(sim.data()->cam_xpos + 3 * id);
  Mat3 r;  // columns: camera x (right), y (up), z (backwards)
  for (int i = 0; i < 9; ++i) r(i / 3, i % 3) = sim.data()->cam_xmat[9 * id + i];
  const Vec3 c = r.transpose() * (p - eye);
  const double f = 0.5 * h / std::tan(0.5 * sim.model()->cam_fovy[id] * M_PI / 180.0);
  return {0.5 * w + f * c.x() / -c.z(), 0.5 * h - f * c.y() / -c.z()};
}

}  // namespace

TEST_CASE("a rendered frame is not blank and shows the vehicle where the camera projects it") {
  Simulation sim = SmallScene(Vec3(1, 1, 1));
  Renderer renderer(&sim, RenderSettings(320, 240, Quality::kFast));
  Image with;
  renderer.Render(CameraSpec{CameraKind::kOverview, ""}, Overlay(), &with);
  REQUIRE(with.width == 320);
  REQUIRE(with.rgb.size() == 320u * 240u * 3u);
  // not blank: the pixels differ a lot
  int low = 255, high = 0;
  for (const uint8_t v : with.rgb) {
    low = std::min<int>(low, v);
    high = std::max<int>(high, v);
  }
  CHECK(high - low > 100);

  // the same view with the vehicle moved out of sight: pixels change near its projection only
  sim.SetVehicleState(State{Vec3(1, 1, -50), Vec3::Zero(), Quat::Identity(), Vec3::Zero()});
  Image without;
  renderer.Render(CameraSpec{CameraKind::kOverview, ""}, Overlay(), &without);
  const Eigen::Vector2d at = Project(sim, model_names::kOverviewCamera, Vec3(1, 1, 1), 320, 240);
  long near = 0, far = 0;
  for (int y = 0; y < 240; ++y) {
    for (int x = 0; x < 320; ++x) {
      int difference = 0;
      for (int k = 0; k < 3; ++k)
        difference += std::abs(with.Pixel(x, y)[k] - without.Pixel(x, y)[k]);
      if (difference < 30) continue;
      (std::hypot(x - at.x(), y - at.y()) < 12 ? near : far) += 1;
    }
  }
  CHECK(near >= 3);    // the vehicle is a few pixels wide at this distance
  CHECK(far <= near);  // and its shadow-free absence changes little else
}

TEST_CASE("a size above the scene's off-screen buffer fails with a clear message") {
  Simulation sim = SmallScene(Vec3(1, 1, 1));
  CHECK_THROWS_WITH_AS(Renderer(&sim, RenderSettings(2560, 1440, Quality::kFast)),
                       doctest::Contains("does not fit the scene's off-screen buffer 1920x1080"),
                       std::invalid_argument);
}

TEST_CASE("a PNG reads back with the same pixels") {
  Simulation sim = SmallScene(Vec3(1, 1, 1));
  Renderer renderer(&sim, RenderSettings(160, 120, Quality::kPretty));
  Image frame;
  renderer.Render(CameraSpec{CameraKind::kChase, ""}, Overlay(), &frame);
  Image back;
  REQUIRE(DecodePng(EncodePng(frame), &back));
  CHECK(back.width == frame.width);
  CHECK(back.height == frame.height);
  CHECK(back.rgb == frame.rgb);
  CHECK_FALSE(DecodePng("not a png", &back));
}

TEST_CASE("an MP4 reads back as H.264 with its size and duration x fps frames") {
  const testing::TempDir dir;
  const std::string path = (dir.path() / "clip.mp4").string();
  Simulation sim = SmallScene(Vec3(1, 1, 1));
  Renderer renderer(&sim, RenderSettings(320, 240, Quality::kFast));
  const int fps = 25;
  const int frames = 50;  // 2 s
  {
    VideoEncoder video(path, 320, 240, fps);
    Image frame;
    for (int i = 0; i < frames; ++i) {
      sim.SetVehicleState(
          State{Vec3(1 + 0.02 * i, 1, 1), Vec3::Zero(), Quat::Identity(), Vec3::Zero()});
      renderer.Render(CameraSpec{CameraKind::kOverview, ""}, Overlay(), &frame);
      video.AddFrame(frame);
    }
    video.Finish();
    CHECK(video.frames_written() == frames);
  }
  CHECK_FALSE(std::filesystem::exists(path + ".partial"));
  AVFormatContext* format = nullptr;
  REQUIRE(avformat_open_input(&format, path.c_str(), nullptr, nullptr) == 0);
  REQUIRE(avformat_find_stream_info(format, nullptr) >= 0);
  REQUIRE(format->nb_streams == 1);
  const AVCodecParameters* codec = format->streams[0]->codecpar;
  CHECK(codec->codec_id == AV_CODEC_ID_H264);
  CHECK(codec->width == 320);
  CHECK(codec->height == 240);
  CHECK(codec->format == AV_PIX_FMT_YUV420P);
  // count the packets (frames) and check the duration
  AVPacket* packet = av_packet_alloc();
  int count = 0;
  while (av_read_frame(format, packet) >= 0) {
    ++count;
    av_packet_unref(packet);
  }
  av_packet_free(&packet);
  const double seconds = static_cast<double>(format->duration) / AV_TIME_BASE;
  avformat_close_input(&format);
  CHECK(std::abs(count - frames) <= 1);
  CHECK(seconds == doctest::Approx(2.0).epsilon(0.05));
}

TEST_CASE("an unfinished video leaves no file") {
  const testing::TempDir dir;
  const std::string path = (dir.path() / "cut.mp4").string();
  {
    VideoEncoder video(path, 64, 48, 10);
    Image frame{64, 48, std::vector<uint8_t>(64 * 48 * 3, 128)};
    video.AddFrame(frame);
  }  // destroyed without Finish(): as when a run is interrupted
  CHECK_FALSE(std::filesystem::exists(path));
  CHECK_FALSE(std::filesystem::exists(path + ".partial"));
  CHECK_THROWS_AS(VideoEncoder(path, 65, 48, 10), std::runtime_error);  // odd width
}

}  // namespace aerobox

namespace aerobox {

TEST_CASE("a renderer leaves the shared model's visual settings as they were") {
  Simulation sim = SmallScene(Vec3(1, 1, 1));
  const int width = sim.model()->vis.global.offwidth;
  const int height = sim.model()->vis.global.offheight;
  const int shadow = sim.model()->vis.quality.shadowsize;
  const int samples = sim.model()->vis.quality.offsamples;
  {
    Renderer small(&sim, RenderSettings(160, 120, Quality::kFast));
    CHECK(sim.model()->vis.global.offwidth == width);
    CHECK(sim.model()->vis.global.offheight == height);
    CHECK(sim.model()->vis.quality.shadowsize == shadow);
    CHECK(sim.model()->vis.quality.offsamples == samples);
  }
  // a second renderer on the same model may still be larger than the first one
  CHECK_NOTHROW(Renderer(&sim, RenderSettings(640, 480, Quality::kFast)));
}

TEST_CASE("a video whose final rename fails throws once and frees everything once") {
  const testing::TempDir dir;
  // the target is a folder: the rename of the finished file onto it fails
  const std::filesystem::path target = dir.path() / "video.mp4";
  std::filesystem::create_directories(target / "inside");
  {
    VideoEncoder video(target.string(), 64, 48, 10);
    Image frame;
    frame.width = 64;
    frame.height = 48;
    frame.rgb.assign(64 * 48 * 3, 128);
    video.AddFrame(frame);
    CHECK_THROWS_AS(video.Finish(), std::runtime_error);
  }  // the destructor releases again: every pointer was cleared, nothing is freed twice
  CHECK_FALSE(std::filesystem::exists(target.string() + ".partial"));
  CHECK(std::filesystem::is_directory(target));
}

}  // namespace aerobox

namespace aerobox {

TEST_CASE("the chase camera moves in front of a box that stands between it and the vehicle") {
  // the vehicle 0.5 m in front of the block's far face, heading +x: the camera, 1.4 m behind,
  // would sit inside the block
  Simulation blocked = SmallScene(Vec3(3.5, 2.75, 0.75));
  Renderer renderer(&blocked, RenderSettings(160, 120, Quality::kFast));
  Image image;
  renderer.Render(CameraSpec{CameraKind::kChase, ""}, Overlay(), &image);
  // along the line of sight the face is 0.5 m / cos(22 deg) = 0.54 m back; 5 cm in front of it
  CHECK(renderer.last_chase_distance() ==
        doctest::Approx(0.5 / std::cos(22 * M_PI / 180) - 0.05).epsilon(0.02));
  // in the open the camera keeps its distance
  Simulation open = SmallScene(Vec3(1.5, 1, 1));
  Renderer free_view(&open, RenderSettings(160, 120, Quality::kFast));
  free_view.Render(CameraSpec{CameraKind::kChase, ""}, Overlay(), &image);
  CHECK(free_view.last_chase_distance() == doctest::Approx(RenderSettings().chase_distance));
}

}  // namespace aerobox

namespace aerobox {
namespace {

// Pixels that differ between two renders of one view and pass `test(after, before)` (RGB).
template <typename Test>
int CountChanged(const Image& before, const Image& after, Test&& test) {
  int count = 0;
  for (int y = 0; y < before.height; ++y) {
    for (int x = 0; x < before.width; ++x) {
      const std::uint8_t* a = before.Pixel(x, y);
      const std::uint8_t* b = after.Pixel(x, y);
      if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2]) continue;
      count += test(b, a);
    }
  }
  return count;
}

}  // namespace

TEST_CASE("the overview's top-down inset fills the top-right corner and only that") {
  Simulation sim = SmallScene(Vec3(1, 1, 1));
  Renderer renderer(&sim, RenderSettings(240, 180, Quality::kFast));
  Image plain, inset;
  Overlay overlay;
  renderer.Render(CameraSpec{CameraKind::kOverview, ""}, overlay, &plain);
  overlay.top_inset = true;
  renderer.Render(CameraSpec{CameraKind::kOverview, ""}, overlay, &inset);
  // pixels that differ, in the top-right third (rows top-down) and elsewhere
  int corner = 0, elsewhere = 0;
  for (int y = 0; y < 180; ++y) {
    for (int x = 0; x < 240; ++x) {
      const size_t i = (static_cast<size_t>(y) * 240 + x) * 3;
      const bool differs = plain.rgb[i] != inset.rgb[i] || plain.rgb[i + 1] != inset.rgb[i + 1] ||
                           plain.rgb[i + 2] != inset.rgb[i + 2];
      const bool in_corner = x >= 240 - 80 - 4 && y < 60 + 4;
      (in_corner ? corner : elsewhere) += differs;
    }
  }
  CHECK(corner > 80 * 60 / 4);  // the inset draws a picture of its own there
  CHECK(elsewhere == 0);
}

TEST_CASE("the wind shows as a cyan arrow at the vehicle") {
  Simulation sim = SmallScene(Vec3(1, 1, 1));
  Renderer renderer(&sim, RenderSettings(480, 360, Quality::kFast));
  const auto cyan = [](const Image& image) {
    int count = 0;
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) {
        const std::uint8_t* p = image.Pixel(x, y);
        count += p[0] < 90 && p[1] > 150 && p[2] > 170;
      }
    }
    return count;
  };
  Image still, windy;
  Overlay overlay;
  renderer.Render(CameraSpec{CameraKind::kOverview, ""}, overlay, &still);
  overlay.wind_W = Vec3(4, 0, 0);
  overlay.wind_origin = Vec3(1, 1, 1.15);
  renderer.Render(CameraSpec{CameraKind::kOverview, ""}, overlay, &windy);
  CHECK(cyan(still) == 0);
  CHECK(cyan(windy) > 40);  // a 1.2 m arrow seen from the overview camera
}

TEST_CASE("a path replanning gave up is drawn in grey") {
  Simulation sim = SmallScene(Vec3(1, 1, 1));
  Renderer renderer(&sim, RenderSettings(480, 360, Quality::kFast));
  Image plain, abandoned;
  Overlay overlay;
  renderer.Render(CameraSpec{CameraKind::kOverview, ""}, overlay, &plain);
  overlay.abandoned.push_back({Vec3(0.5, 3.5, 1.0), Vec3(3.5, 3.5, 1.0), Vec3(3.5, 0.5, 1.0)});
  renderer.Render(CameraSpec{CameraKind::kOverview, ""}, overlay, &abandoned);
  // pixels the path changed into grey: r, g and b alike
  const int grey = CountChanged(plain, abandoned, [](const std::uint8_t* b, const std::uint8_t*) {
    return std::max({b[0], b[1], b[2]}) - std::min({b[0], b[1], b[2]}) < 25;
  });
  CHECK(grey > 100);  // 6 m of line, 2 pixels wide
}

TEST_CASE("where a flight hit a box is marked in magenta") {
  Simulation sim = SmallScene(Vec3(1, 1, 1));
  Renderer renderer(&sim, RenderSettings(480, 360, Quality::kFast));
  Image plain, marked;
  Overlay overlay;
  renderer.Render(CameraSpec{CameraKind::kOverview, ""}, overlay, &plain);
  overlay.collision = Vec3(2, 2, 1);
  renderer.Render(CameraSpec{CameraKind::kOverview, ""}, overlay, &marked);
  // pixels the marker changed into red and blue well above green
  const int magenta = CountChanged(plain, marked, [](const std::uint8_t* b, const std::uint8_t*) {
    return b[0] > b[1] + 60 && b[2] > b[1] + 60;
  });
  CHECK(magenta > 50);  // a sphere of a few pixels' radius at least
}

TEST_CASE("the vehicle is marked where a camera sees the whole map") {
  Simulation sim = SmallScene(Vec3(1, 1, 1));
  Renderer renderer(&sim, RenderSettings(480, 360, Quality::kFast));
  Image plain, marked;
  Overlay overlay;
  renderer.Render(CameraSpec{CameraKind::kOverview, ""}, overlay, &plain);
  overlay.vehicle = sim.VehicleState().p_W;
  renderer.Render(CameraSpec{CameraKind::kOverview, ""}, overlay, &marked);
  // pixels the see-through dark marker darkened
  const int darker = CountChanged(plain, marked, [](const std::uint8_t* b, const std::uint8_t* a) {
    return b[0] + b[1] + b[2] + 30 < a[0] + a[1] + a[2];
  });
  CHECK(darker > 50);
}

TEST_CASE("cameras by name: one parser for the command and the package, unknown names refused") {
  CHECK(ParseCamera("chase").kind == CameraKind::kChase);
  CHECK(ParseCamera("overview").kind == CameraKind::kOverview);
  CHECK(ParseCamera("top").kind == CameraKind::kTop);
  CHECK_THROWS_WITH_AS(ParseCamera("side"), "expected chase, overview or top, got 'side'",
                       std::invalid_argument);
}

}  // namespace aerobox
