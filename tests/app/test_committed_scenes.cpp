// The scenes shipped in scenes/ are current, and every published map becomes a loadable scene.
#include <doctest/doctest.h>

#include "scenario/scenario.h"
#include "sim/mujoco_messages.h"
#include "sim/simulation.h"
#include "test_support.h"

namespace aerobox {
namespace fs = std::filesystem;

TEST_CASE("every scene in scenes/ has a scenario, a map and an up-to-date scene.xml") {
  int scenes = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(testing::SourceDir() / "scenes")) {
    if (!entry.is_directory()) continue;
    ++scenes;
    const fs::path folder = entry.path();
    CAPTURE(folder.string());
    REQUIRE(fs::exists(folder / "scenario.toml"));
    const FlightSetup setup = LoadFlightSetup((folder / "scenario.toml").string(), {});
    CHECK(setup.name == folder.filename().string());
    CHECK(setup.start_origin != "default");  // every shipped scenario names its start
    CHECK(setup.goal);
    const std::string generated = SceneMjcfFor(setup);
    CHECK_MESSAGE(testing::ReadFile(folder / "scene.xml") == generated,
                  "stale scene.xml: run tools/regenerate_scenes.sh");
    TakeMujocoWarnings();
    const Simulation sim = Simulation::FromXml(generated, (folder / "scene.xml").string());
    CHECK(TakeMujocoWarnings().empty());
    CHECK(sim.model()->ngeom > static_cast<int>(setup.map.boxes.size()));
  }
  CHECK(scenes >= 13);  // every MIT-licensed map of ../shared/maps (SOURCES.md)
}

TEST_CASE("every published map becomes a scene that MuJoCo loads") {
  AEROBOX_REQUIRE_SHARED_MAPS(maps);
  int count = 0;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(maps)) {
    const std::string ext = entry.path().extension().string();
    if (!entry.is_regular_file() ||
        entry.path().filename().string().find(".startgoal.") != std::string::npos ||
        (ext != ".txt" && ext != ".json" && ext != ".csv")) {
      continue;
    }
    CAPTURE(entry.path().string());
    const FlightSetup setup = LoadFlightSetup(entry.path().string(), {});
    TakeMujocoWarnings();
    const Simulation sim = Simulation::FromXml(SceneMjcfFor(setup), entry.path().string());
    CHECK(TakeMujocoWarnings().empty());
    int boxes = 0;
    for (int g = 0; g < sim.model()->ngeom; ++g) {
      const char* name = mj_id2name(sim.model(), mjOBJ_GEOM, g);
      boxes += name != nullptr && std::string(name).rfind("block_", 0) == 0;
    }
    CHECK(boxes == static_cast<int>(setup.map.boxes.size()));
    ++count;
  }
  CHECK(count == 22);
}

}  // namespace aerobox
