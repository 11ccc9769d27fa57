#include <doctest/doctest.h>

#include "common/error.h"
#include "map/map.h"

namespace aerobox {

TEST_CASE("DefaultStart finds a free spot on the floor clear of every box") {
  Map map;
  map.name = "grid";
  map.bounds = {Vec3(0, 0, 0), Vec3(4.5, 6.5, 3)};
  // a pillar at the corner where the scan begins
  map.boxes.push_back({{Vec3(0, 0, 0), Vec3(0.5, 0.5, 3)}, Vec3(1, 0, 0), "block_0", 1});
  const std::optional<Vec3> start = DefaultStart(map, 0.3, 0.025);
  REQUIRE(start);
  CHECK(start->z() == doctest::Approx(0.025));
  const Aabb around{start->array() - 0.3, start->array() + 0.3};
  CHECK_FALSE(FirstOverlappingBox(map, around));
  CHECK(start->x() > 0.8 - 1e-9);  // the first grid point clear of the pillar by 0.3 m

  map.boxes.push_back({map.bounds, Vec3(1, 0, 0), "block_1", 2});  // fills everything
  CHECK_FALSE(DefaultStart(map, 0.3, 0.025));
}

TEST_CASE("DefaultStart rests on a block where blocks cover the floor") {
  // a course map that models the floor and the ceiling as slabs
  Map map;
  map.name = "slabs";
  map.bounds = {Vec3(0, 0, 0), Vec3(4, 4, 3)};
  map.boxes.push_back({{Vec3(0, 0, 0), Vec3(4, 4, 0.2)}, Vec3(1, 0, 0), "floor_slab", 1});
  map.boxes.push_back({{Vec3(0, 0, 2.8), Vec3(4, 4, 3)}, Vec3(1, 0, 0), "ceiling_slab", 2});
  const std::optional<Vec3> start = DefaultStart(map, 0.3, 0.025);
  REQUIRE(start);
  CHECK(start->z() == doctest::Approx(0.2 + 0.025));  // resting on the floor slab
  const Aabb vehicle{start->array() - 0.025, start->array() + 0.025};
  CHECK_FALSE(FirstOverlappingBox(map, vehicle));
}

TEST_CASE("ValidateMap rejects what no reader should produce") {
  Map map;
  map.source = "m.txt";
  map.bounds = {Vec3(0, 0, 0), Vec3(1, 1, 1)};
  map.boxes.push_back({{Vec3(0, 0, 0), Vec3(1, 1, 1)}, Vec3(1, 0, 0), "a", 3});
  CHECK_NOTHROW(ValidateMap(map));
  map.boxes.push_back({{Vec3(0, 0, 0), Vec3(1, 1, 1)}, Vec3(1, 0, 0), "a", 4});
  CHECK_THROWS_WITH_AS(ValidateMap(map), "m.txt:4: a: box name is used twice", InputError);
  map.boxes.back().name = "b";
  map.boxes.back().rgb = Vec3(2, 0, 0);
  CHECK_THROWS_WITH_AS(ValidateMap(map), "m.txt:4: b: colour components must lie in [0, 1]",
                       InputError);
  map.boxes.back().rgb = Vec3(0, 0, 1);
  map.boxes.back().extent.max.x() = 2e6;  // a typo or garbage, not a map
  CHECK_THROWS_WITH_AS(ValidateMap(map), "m.txt:4: b: coordinates must lie within +-1e+06 m",
                       InputError);
}

TEST_CASE("error messages escape control characters and bytes that are not UTF-8") {
  const InputError error({"m.txt", 2}, "key\x01", std::string("bad '\0\xff' caf\xc3\xa9", 14));
  CHECK(std::string(error.what()) == "m.txt:2: key\\x01: bad '\\x00\\xff' caf\xc3\xa9");
}

}  // namespace aerobox
