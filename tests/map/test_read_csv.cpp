#include <doctest/doctest.h>

#include "map/map_test_util.h"

namespace aerobox {
namespace {

using testing::ReadError;
using testing::ReadText;

const char* const kHead =
    "lat0 37.792480, lon0 -122.397450\nposX,posY,posZ,halfSizeX,halfSizeY,halfSizeZ\n";

Map Csv(const std::string& text) { return ReadText(text, "city/colliders.csv"); }
std::string CsvError(const std::string& text) { return ReadError(text, "city/colliders.csv"); }

}  // namespace

TEST_CASE("CSV: centre and half-size rows and bounds are the union of the boxes") {
  const Map map = Csv(std::string(kHead) +
                      "-310.2389,-439.2315,85.5,5,5,85.5\r\n"
                      "-300.2389,-439.2315,85.5,5,5,85.5\n\n"
                      "10, 20, 0.5, 1, 2, 0.6");
  REQUIRE(map.boxes.size() == 3);
  CHECK(map.boxes[0].extent.min.isApprox(Vec3(-315.2389, -444.2315, 0)));
  CHECK(map.boxes[0].extent.max.isApprox(Vec3(-305.2389, -434.2315, 171)));
  CHECK(map.boxes[2].line == 6);
  CHECK(map.bounds.min.isApprox(Vec3(-315.2389, -444.2315, -0.1)));
  CHECK(map.bounds.max.isApprox(Vec3(11, 22, 171)));
}

TEST_CASE("CSV: bad input names the file, the line and the field") {
  CHECK(CsvError("") == "city/colliders.csv:1: the map is empty");
  CHECK(CsvError("lat 1, lon 2\n").rfind("city/colliders.csv:1: origin:", 0) == 0);
  CHECK(CsvError("lat0 x, lon0 2\n") == "city/colliders.csv:1: lat0: 'x' is not a number");
  CHECK(CsvError("lat0 1, lon0 2\n") ==
        "city/colliders.csv:1: header: the column header is missing");
  CHECK(CsvError("lat0 1, lon0 2\nx,y,z\n").rfind("city/colliders.csv:2: header:", 0) == 0);
  CHECK(CsvError(std::string(kHead)) == "city/colliders.csv: rows: the map has no buildings");
  CHECK(CsvError(std::string(kHead) + "1,2,3,4,5\n") ==
        "city/colliders.csv:3: row: expected 6 comma-separated numbers, found 5 fields");
  CHECK(CsvError(std::string(kHead) + "1,2,3,4,5,6\n1,2,three,4,5,6\n") ==
        "city/colliders.csv:4: posZ: 'three' is not a number");
  CHECK(CsvError(std::string(kHead) + "1,2,3,4,-5,6\n") ==
        "city/colliders.csv:3: halfSizeY: half-size must be positive");
  CHECK(CsvError(std::string(kHead) + "1,2,3,4,5,inf\n") ==
        "city/colliders.csv:3: halfSizeZ: 'inf' is not a finite number");
}

TEST_CASE("the format is chosen by extension, else by content") {
  CHECK(DetectMapFormat("a/b.JSON", "") == MapFormat::kJson);
  CHECK(DetectMapFormat("a/b.csv", "{") == MapFormat::kCsv);
  CHECK(DetectMapFormat("a/b.txt", "{") == MapFormat::kTxt);
  CHECK(DetectMapFormat("map", "  \n{\"bounds\"") == MapFormat::kJson);
  CHECK(DetectMapFormat("map", "lat0 37, lon0 -122") == MapFormat::kCsv);
  CHECK(DetectMapFormat("map", "boundary 0 0 0 1 1 1") == MapFormat::kTxt);
}

}  // namespace aerobox
