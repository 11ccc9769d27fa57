#include <mujoco/mujoco.h>

#include <sstream>

#include "outputs/flight_outputs.h"
#include "perception/depth_camera.h"
#include "render/renderer.h"
#include "scenario/scenario.h"
#include "test_support.h"

namespace aerobox {
namespace {

float Alpha(const Simulation& sim, const std::string& geom) {
  const int id = mj_name2id(sim.model(), mjOBJ_GEOM, geom.c_str());
  REQUIRE(id >= 0);
  return sim.model()->geom_rgba[4 * id + 3];
}

}  // namespace

TEST_CASE("unknown boxes are drawn faint until revealed, then whole") {
  const std::string scenario =
      (testing::SourceDir() / "scenes" / "maze_unknown" / "scenario.toml").string();
  const FlightSetup setup = LoadFlightSetup(scenario, SetupOverrides());
  REQUIRE(setup.HasUnknown());
  std::vector<size_t> unknown, known;
  for (size_t i = 0; i < setup.map.boxes.size(); ++i) {
    (setup.unknown[i] ? unknown : known).push_back(i);
  }
  REQUIRE(unknown.size() >= 2);
  Simulation sim = Simulation::FromXml(SceneMjcfFor(setup), "maze_unknown");
  RenderOptions options;
  options.width = 160;
  options.height = 120;
  options.video = false;
  std::ostringstream err;
  RenderOutputs outputs(
      (std::filesystem::temp_directory_path() / "aerobox_render_outputs").string(), setup, options,
      err);
  outputs.OnScene(sim, {});
  for (const size_t i : unknown) CHECK(Alpha(sim, setup.map.boxes[i].name) < 0.5f);
  for (const size_t i : known) CHECK(Alpha(sim, setup.map.boxes[i].name) == 1.0f);
  // the sensor reveals the first unknown box: it alone turns whole
  std::vector<double> revealed_at(setup.map.boxes.size(), -1.0);
  revealed_at[unknown[0]] = 1.25;
  outputs.OnDiscovery(revealed_at, {});
  CHECK(Alpha(sim, setup.map.boxes[unknown[0]].name) == 1.0f);
  for (size_t k = 1; k < unknown.size(); ++k) {
    CHECK(Alpha(sim, setup.map.boxes[unknown[k]].name) < 0.5f);
  }
}

}  // namespace aerobox

namespace aerobox {

TEST_CASE("a depth camera's frame is coloured by depth and drawn in the frame's top right corner") {
  DepthImage depth;
  depth.width = 4;
  depth.height = 3;
  depth.depth.assign(12, 0.0f);  // nothing within range ...
  depth.depth[0] = 0.5f;         // ... but a near point at the top left
  depth.depth[11] = 5.0f;        // and one at the range, bottom right
  const Image coloured = ColourDepth(depth, 5.0);
  REQUIRE(coloured.width == 4);
  REQUIRE(coloured.height == 3);
  const std::uint8_t* near = coloured.Pixel(0, 0);
  const std::uint8_t* far = coloured.Pixel(3, 2);
  const std::uint8_t* none = coloured.Pixel(1, 1);
  CHECK(near[0] > 200);  // warm
  CHECK(far[0] < 60);    // dark
  CHECK((none[0] == 0 && none[1] == 0 && none[2] == 0));
  Image frame;
  frame.width = 160;
  frame.height = 120;
  frame.rgb.assign(160 * 120 * 3, 7);
  DrawInset(coloured, &frame);
  // a quarter of the width (40 px), 8 px in from the top right corner, framed in white
  CHECK(frame.Pixel(160 - 8 - 40, 8)[0] == near[0]);     // the inset's top left: the near point
  CHECK(frame.Pixel(160 - 8 - 1, 8 + 29)[0] == far[0]);  // its bottom right: the far one
  CHECK(frame.Pixel(160 - 8 - 41, 8)[0] == 255);         // the white frame
  CHECK(frame.Pixel(10, 60)[0] == 7);                    // the rest untouched
  CHECK(frame.Pixel(160 - 8 - 20, 8 + 31)[0] == 7);
}

}  // namespace aerobox
