#include <doctest/doctest.h>

#include <sstream>
#include <stdexcept>

#include "map/forest.h"
#include "map/map_reader.h"

using namespace aerobox;

TEST_CASE("forest: Fast-Planner's density, seeded, the ends clear, read back the same") {
  ForestParams params;  // 40 x 20 x 5 m, 150 pillars 1.0-1.4 m wide
  params.bars = 10;
  const Map forest = MakeForest(params);
  REQUIRE(forest.boxes.size() == 160);
  CHECK(forest.bounds.max == Vec3(40, 20, 5));
  for (size_t i = 0; i < 150; ++i) {
    const Aabb& b = forest.boxes[i].extent;
    CHECK(b.min.z() == 0.0);
    CHECK(b.max.z() == 5.0);
    CHECK(b.Size().x() >= 1.0 - 1e-9);
    CHECK(b.Size().x() <= 1.4 + 1e-9);
    CHECK(b.min.x() >= 3.0 - 1e-9);
    CHECK(b.max.x() <= 37.0 + 1e-9);
    CHECK(b.IsInside(forest.bounds));
  }
  for (size_t i = 150; i < 160; ++i) {
    CHECK(forest.boxes[i].extent.Size().minCoeff() == doctest::Approx(0.2));
    CHECK(forest.boxes[i].extent.IsInside(forest.bounds));
  }
  REQUIRE(forest.start.has_value());
  REQUIRE(forest.goal.has_value());
  CHECK(*forest.start == Vec3(1, 10, 1));
  CHECK(*forest.goal == Vec3(39, 10, 1));
  // the same seed, the same forest; another seed, another
  CHECK(MakeForest(params).boxes[42].extent.min == forest.boxes[42].extent.min);
  params.seed = 2;
  CHECK(MakeForest(params).boxes[42].extent.min != forest.boxes[42].extent.min);
  // written as flightsim's JSON and read back: the same boxes, start and goal
  std::istringstream text(MapJson(forest));
  const Map read = ReadJsonMap(text, "forest.json");
  REQUIRE(read.boxes.size() == forest.boxes.size());
  for (size_t i = 0; i < read.boxes.size(); ++i) {
    CHECK(read.boxes[i].extent.min == forest.boxes[i].extent.min);
    CHECK(read.boxes[i].extent.max == forest.boxes[i].extent.max);
    CHECK(read.boxes[i].name == forest.boxes[i].name);
  }
  CHECK(read.bounds.max == forest.bounds.max);
  CHECK(*read.start == *forest.start);
  CHECK(*read.goal == *forest.goal);
}

TEST_CASE("forest: bad parameters are refused naming the key") {
  ForestParams params;
  params.width_max = 0.5;
  CHECK_THROWS_WITH_AS(MakeForest(params), doctest::Contains("forest.width_max"),
                       std::invalid_argument);
  params = ForestParams();
  params.pillars = -1;
  CHECK_THROWS_WITH_AS(MakeForest(params), doctest::Contains("forest.pillars"),
                       std::invalid_argument);
  params = ForestParams();
  params.clear_ends = 19;
  CHECK_THROWS_WITH_AS(MakeForest(params), doctest::Contains("forest.clear_ends"),
                       std::invalid_argument);
}
