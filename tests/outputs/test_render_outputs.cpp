#include <mujoco/mujoco.h>

#include <sstream>

#include "outputs/flight_outputs.h"
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
