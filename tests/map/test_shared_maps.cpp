// Every published map in ../shared/maps parses with the right number of boxes.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "map/map_reader.h"
#include "test_support.h"

namespace aerobox {
namespace {

Map ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in);
  std::stringstream text;
  text << in.rdbuf();
  const std::string content = text.str();
  std::istringstream stream(content);
  return ReadMap(stream, path.string(), DetectMapFormat(path.string(), content));
}

}  // namespace

TEST_CASE("every published map parses with its number of boxes") {
  AEROBOX_REQUIRE_SHARED_MAPS(maps);
  // counted independently from the files (block lines, JSON "blocks" entries, CSV rows)
  const std::pair<const char*, size_t> expected[] = {
      {"rbe595/map1.txt", 8},
      {"rbe595/map2.txt", 2},
      {"rbe595/map3.txt", 7},
      {"rbe595/map4.txt", 2},
      {"rbe595/p2b_real_map1.txt", 3},
      {"meam620_2015/emptyMap.txt", 0},
      {"meam620_2015/singleCube.txt", 1},
      {"flightsim/grid_forest.json", 12},
      {"flightsim/test_empty.json", 0},
      {"flightsim/test_forest.json", 54},
      {"flightsim/test_impossible.json", 1},
      {"flightsim/test_maze.json", 18},
      {"flightsim/test_over_under.json", 7},
      {"flightsim/test_saw.json", 3},
      {"flightsim/test_slide.json", 5},
      {"flightsim/test_window.json", 8},
      {"rotorpy/2d_vortex_shedding.json", 5},
      {"rotorpy/custom_pillars.json", 3},
      {"rotorpy/double_pillar.json", 2},
      {"rotorpy/grid_forest.json", 12},
      {"rotorpy/pillar.json", 1},
      {"fcnd/colliders.csv", 3845},
  };
  for (const auto& [file, count] : expected) {
    CAPTURE(file);
    const Map map = ReadFile(maps / file);
    CHECK(map.boxes.size() == count);
  }
}

TEST_CASE("published quirks: start and goal from JSON, the maze wall outside its bounds") {
  AEROBOX_REQUIRE_SHARED_MAPS(maps);
  const Map window = ReadFile(maps / "flightsim/test_window.json");
  REQUIRE(window.start);
  CHECK(window.start->isApprox(Vec3(0.7, -4.3, 0.7)));
  CHECK(window.goal->isApprox(Vec3(8, 18, 3)));

  const Map maze = ReadFile(maps / "flightsim/test_maze.json");
  const std::vector<size_t> outside = BoxesOutsideBounds(maze);
  REQUIRE(outside.size() == 1);
  CHECK(maze.boxes[outside[0]].extent.max.x() == doctest::Approx(10.1));

  const Map city = ReadFile(maps / "fcnd/colliders.csv");
  // SOURCES.md: 920 x 920 x 212 m (rounded to metres), bottoms between -0.40 and +0.05 m
  // (rounded to centimetres): the tolerances are those roundings
  const Vec3 size = city.bounds.Size();
  CHECK(std::abs(size.x() - 920) <= 0.5);
  CHECK(std::abs(size.y() - 920) <= 0.5);
  CHECK(std::abs(size.z() - 212) <= 0.5);
  CHECK(std::abs(city.bounds.min.z() - -0.40) <= 0.005);
}

}  // namespace aerobox
