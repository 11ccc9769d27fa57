#include <doctest/doctest.h>

#include <cmath>

#include "map/map_test_util.h"

namespace aerobox {
namespace {

using testing::ReadError;
using testing::ReadText;

Map Json(const std::string& text) { return ReadText(text, "worlds/test.json"); }
std::string JsonError(const std::string& text) { return ReadError(text, "worlds/test.json"); }

}  // namespace

TEST_CASE("JSON: interleaved extents, optional colour, start and goal") {
  const Map map = Json(R"({
    "bounds": {"extents": [0.0, 10.0, -5.0, 20.0, 0.0, 6.0]},
    "blocks": [
        {"extents": [0.0, 10.0, 2.0, 2.5, 0.0, 1.5], "color": [1.0, 0.0, 0.0]},
        {"extents": [3.0, 7.0, 0.0, 0.5, 2.4, 4.5]}
    ],
    "start": [0.7, -4.3, 0.7],
    "goal": [8.0, 18.0, 3.0],
    "resolution": [0.25, 0.25, 0.25], "margin": 0.1, "algorithms": ["astar"]
})");
  CHECK(map.bounds.min.isApprox(Vec3(0, -5, 0)));
  CHECK(map.bounds.max.isApprox(Vec3(10, 20, 6)));
  REQUIRE(map.boxes.size() == 2);
  CHECK(map.boxes[0].extent.min.isApprox(Vec3(0, 2, 0)));
  CHECK(map.boxes[0].extent.max.isApprox(Vec3(10, 2.5, 1.5)));
  CHECK(map.boxes[0].rgb.isApprox(Vec3(1, 0, 0)));
  CHECK(map.boxes[1].rgb.isApprox(Box().rgb));
  CHECK(map.boxes[0].line == 4);
  CHECK(map.boxes[1].line == 5);
  REQUIRE(map.start);
  CHECK(map.start->isApprox(Vec3(0.7, -4.3, 0.7)));
  CHECK(map.goal->isApprox(Vec3(8, 18, 3)));
}

TEST_CASE("JSON: the Infinity token, no blocks, CRLF") {
  const Map map = Json(
      "{\r\n \"bounds\": {\"extents\": [0, 2.0, 0, 4.0, 0, 1.0]},\r\n"
      " \"expected_path_length\": Infinity,\r\n \"margin\": -Infinity, \"timeout\": NaN\r\n}");
  CHECK(map.boxes.empty());
  CHECK(map.bounds_line == 2);
}

TEST_CASE("JSON: colours 0-255 are accepted like the TXT format's") {
  const Map map = Json(R"({"bounds": {"extents": [0,1,0,1,0,1]},
    "blocks": [{"extents": [0,1,0,1,0,1], "color": [0, 255, 51]}]})");
  CHECK(map.boxes[0].rgb.isApprox(Vec3(0, 1, 0.2)));
}

TEST_CASE("JSON: bad input names the file, the line and the field") {
  CHECK(JsonError("") == "worlds/test.json:1: the map is empty");
  CHECK(JsonError("{\"bounds\": {\"extents\": [0,1,0,1,0,1]},\n\"blocks\": [\n{\"extents\": "
                  "[0,1,0,1,0,1], \"colour\": [1, 0, 0]}]}") ==
        "worlds/test.json:3: blocks[0].colour: unknown key (expected extents, color)");
  CHECK(JsonError("{\"bounds\": {\"extents\": [0,1,0,1,0,1]},\n\"blokcs\": []}") ==
        "worlds/test.json:2: blokcs: unknown key (expected bounds, blocks, start, goal, margin, "
        "resolution, timeout, expected_path_length, algorithms)");
  CHECK(JsonError("{\n\"bounds\": {\"extents\": [0,1,0,1,0,1]},\n\"blocks\": [\n{\"extents\": "
                  "[0,1,0,1,0]}]}") ==
        "worlds/test.json:4: blocks[0].extents: expected 6 numbers, found 5");
  CHECK(JsonError("{\"bounds\": {\"extents\": [0,1,0,1,0,1]},\n\"blocks\": [\n{\"extents\": "
                  "[0,1,0,1,\n\"a\",1]}]}") ==
        "worlds/test.json:4: blocks[0].extents[4]: expected a number, found a string");
  CHECK(JsonError("{\"bounds\": {\"extents\": [0,1,0,1,0,1]},\n\"blocks\": [{\"extents\": "
                  "[0,1,0,NaN,0,1]}]}") ==
        "worlds/test.json:2: blocks[0].extents[3]: must be a finite number");
  CHECK(JsonError("{\"bounds\": {\"extents\": [0,1,0,1,0,1]},\n\"blocks\": [\n\n"
                  "{\"extents\": [0,1,5,1,0,1]}]}") ==
        "worlds/test.json:4: block_0: ymin 5 must be less than ymax 1");
  CHECK(JsonError("{\"bounds\": {\"extents\": [0,1,0,1,1,1]}}") ==
        "worlds/test.json:1: boundary: zmin 1 must be less than zmax 1");
  CHECK(JsonError("{\"blocks\": []}") == "worlds/test.json:1: document: missing key \"bounds\"");
  CHECK(JsonError("{\"bounds\": [0,1,0,1,0,1]}") ==
        "worlds/test.json:1: bounds: expected an object, found an array");
  CHECK(JsonError("{\"bounds\": {\"extents\": [0,1,0,1,0,1]},\n\"blocks\": [3]}") ==
        "worlds/test.json:2: blocks[0]: expected an object, found a number");
  CHECK(JsonError("{\"bounds\": {\"extents\": [0,1,0,1,0,1]}, \"start\": [1,2]}") ==
        "worlds/test.json:1: start: expected 3 numbers, found 2");
  CHECK(JsonError("[1, 2]") == "worlds/test.json:1: document: expected an object, found an array");
  // syntax errors point at their line
  CHECK(JsonError("{\n\"bounds\": {\"extents\": [0,1,0,1,0,1]}\n\"blocks\": []}") ==
        "worlds/test.json:3: JSON: expected ',' or '}' in an object");
  CHECK(JsonError("{\"bounds\": {\"extents\": [0,1,0,1,0,1]},\n\n\"x\": [1, 2,") ==
        "worlds/test.json:3: JSON: unexpected end of file");
  CHECK(JsonError("{\"a\": 1, \"a\": 2}") == "worlds/test.json:1: JSON: key \"a\" appears twice");
  CHECK(JsonError("{\"a\": tru}") == "worlds/test.json:1: JSON: expected a value, found 'tru}'");
  CHECK(JsonError("{\"a\": \"x\\q\"}") == "worlds/test.json:1: JSON: unknown escape '\\q'");
  CHECK(JsonError("{} {}") ==
        "worlds/test.json:1: JSON: unexpected text after the end of the document");
  CHECK(JsonError(std::string(100000, '[')) ==
        "worlds/test.json:1: JSON: nested deeper than 64 levels");
}

}  // namespace aerobox

namespace aerobox {

TEST_CASE("JSON: flightsim's matplotlib colour names") {
  const std::string text = R"({"bounds": {"extents": [0, 5, 0, 5, 0, 3]},
    "blocks": [{"extents": [1, 2, 1, 2, 0, 1], "color": "blue"},
               {"extents": [3, 4, 3, 4, 0, 1], "color": "tab:orange"},
               {"extents": [1, 2, 3, 4, 0, 1], "color": "#FF8000"},
               {"extents": [3, 4, 1, 2, 0, 1], "color": "k"}]})";
  std::istringstream in(text);
  const Map map = ReadMap(in, "named.json", MapFormat::kJson);
  REQUIRE(map.boxes.size() == 4);
  CHECK(map.boxes[0].rgb.isApprox(Vec3(0, 0, 1)));
  CHECK(map.boxes[1].rgb.isApprox(Vec3(1.0, 127 / 255.0, 14 / 255.0)));
  CHECK(map.boxes[2].rgb.isApprox(Vec3(1.0, 128 / 255.0, 0)));
  CHECK(map.boxes[3].rgb.isApprox(Vec3(0, 0, 0)));
  std::istringstream bad(R"({"bounds": {"extents": [0, 5, 0, 5, 0, 3]},
    "blocks": [{"extents": [1, 2, 1, 2, 0, 1], "color": "blurple"}]})");
  CHECK_THROWS_WITH_AS(ReadMap(bad, "bad.json", MapFormat::kJson),
                       doctest::Contains("bad.json:2: blocks[0].color: unknown colour name"),
                       InputError);
}

}  // namespace aerobox
