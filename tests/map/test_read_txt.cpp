#include <doctest/doctest.h>

#include "map/map_test_util.h"

namespace aerobox {
namespace {

using testing::ReadError;
using testing::ReadText;

Map Txt(const std::string& text) { return ReadText(text, "maps/test.txt"); }
std::string TxtError(const std::string& text) { return ReadError(text, "maps/test.txt"); }

}  // namespace

TEST_CASE("TXT: boundary and blocks with 0-255 colours") {
  const Map map =
      Txt("# map1\n\nboundary 0.0 -5.0 0.0 10.0 20.0 6.0\n\n"
          "block  0.0  2.0  0.0 10.0  2.5  1.5 255   0   0\n"
          "block 3 0 2.4 7 0.5 4.5 0 127.5 255\n");
  CHECK(map.name == "test");
  CHECK(map.bounds.min.isApprox(Vec3(0, -5, 0)));
  CHECK(map.bounds.max.isApprox(Vec3(10, 20, 6)));
  CHECK(map.bounds_line == 3);
  REQUIRE(map.boxes.size() == 2);
  CHECK(map.boxes[0].extent.max.isApprox(Vec3(10, 2.5, 1.5)));
  CHECK(map.boxes[0].rgb.isApprox(Vec3(1, 0, 0)));
  CHECK(map.boxes[1].rgb.isApprox(Vec3(0, 0.5, 1)));
  CHECK(map.boxes[0].line == 5);
  CHECK(map.boxes[1].line == 6);
  CHECK(map.boxes[1].name == "block_1");
  CHECK_FALSE(map.start);
}

TEST_CASE("TXT: every quirk seen in published maps parses") {
  SUBCASE("CRLF line endings and no final newline") {
    const Map map =
        Txt("# c\r\nboundary 0 0 0 45 35 6\r\nblock 1 1 1 3 3 3 0 255 0\r\n"
            "block 20 10 0 21 20 6 0 0 255");
    CHECK(map.boxes.size() == 2);
    CHECK(map.boxes[1].line == 4);
    CHECK(map.boxes[1].rgb.isApprox(Vec3(0, 0, 1)));
  }
  SUBCASE("boundary after blocks, colours written 255.000000") {
    const Map map =
        Txt("block 3.100000 0.000000 2.100000 3.900000 5.000000 6.000000 "
            "255.000000 0.000000 0.000000\n\n"
            "boundary 0.000000 0.000000 0.000000 20.000000 5.000000 6.000000\n");
    CHECK(map.boxes.size() == 1);
    CHECK(map.bounds.max.x() == 20.0);
    CHECK(map.bounds_line == 3);
  }
  SUBCASE("colours 0-1 and colours missing") {
    const Map map = Txt("boundary 0 0 0 10 10 6\nblock 1 1 1 2 2 2 0 0.5 1\nblock 3 3 3 4 4 4\n");
    CHECK(map.boxes[0].rgb.isApprox(Vec3(0, 0.5, 1)));
    CHECK(map.boxes[1].rgb.isApprox(Box().rgb));
  }
  SUBCASE("a boundary with 3 extra colour numbers") {
    const Map map = Txt("boundary 0 0 0 10 10 6 255 255 255\n");
    CHECK(map.bounds.max.isApprox(Vec3(10, 10, 6)));
    CHECK(map.boxes.empty());
  }
  SUBCASE("tabs, blank lines, inline comments and commented-out blocks") {
    const Map map =
        Txt("\n\t\nboundary\t0 0 0\t10 10 6   # the room\n"
            "#block 1 1 1 2 2 2 255 0 0\n  # block 1 1 1 2 2 2\n"
            "\tblock 1 1 1 2 2 2\t255 0 0\t\n");
    REQUIRE(map.boxes.size() == 1);
    CHECK(map.boxes[0].line == 6);
  }
  SUBCASE("lone CR line endings and a byte-order mark") {
    const Map map =
        Txt("\xEF\xBB\xBF"
            "boundary 0 0 0 1 1 1\rblock 0 0 0 0.5 0.5 0.5\r");
    CHECK(map.boxes.size() == 1);
    CHECK(map.boxes[0].line == 2);
  }
  SUBCASE("overlapping blocks and blocks outside the bounds are kept") {
    const Map map =
        Txt("boundary 0 0 0 10 10 3\nblock 0 0 0 5 5 3\nblock 4 4 0 6 6 3\nblock 9 0 0 10.1 1 3\n");
    CHECK(map.boxes.size() == 3);
    CHECK(BoxesOutsideBounds(map) == std::vector<size_t>{2});
  }
}

TEST_CASE("TXT: bad input names the file, the line and the field") {
  CHECK(TxtError("boundary 0 0 0 10 10 6\nblok 1 1 1 2 2 2\n") ==
        "maps/test.txt:2: keyword: unknown keyword 'blok' (expected 'boundary' or 'block')");
  CHECK(TxtError("boundary 0 0 0 10 10 6\n\nblock 1 1 1 2 2\n")
            .rfind("maps/test.txt:3: block: expected 6 numbers", 0) == 0);
  CHECK(TxtError("boundary 0 0 0 10 10 6\nblock 1 1 1 2 2 2 255 0\n")
            .find(":2: block: expected 6 numbers") != std::string::npos);
  CHECK(TxtError("boundary 0 0 0 10 10 6\nblock 1 1 abc 2 2 2\n") ==
        "maps/test.txt:2: block zmin: 'abc' is not a number");
  CHECK(TxtError("boundary 0 0 0 10 10 6\nblock 1 1 1 2 nan 2\n") ==
        "maps/test.txt:2: block ymax: 'nan' is not a finite number");
  CHECK(TxtError("boundary 0 0 0 10 10 6\nblock 1 1 1 2 2 Infinity\n")
            .find(":2: block zmax: 'Infinity' is not a finite number") != std::string::npos);
  CHECK(TxtError("boundary 0 0 0 10 10 6\n\n\nblock 3 1 1 2 2 2\n") ==
        "maps/test.txt:4: block_0: xmin 3 must be less than xmax 2");
  CHECK(TxtError("block 1 1 1 2 2 2\nboundary 0 0 6 10 10 0\n") ==
        "maps/test.txt:2: boundary: zmin 6 must be less than zmax 0");
  CHECK(TxtError("") == "maps/test.txt:1: the map is empty");
  CHECK(TxtError("\r\n  \n# only a comment\n") ==
        "maps/test.txt:1: boundary: no 'boundary' line in the file");
  CHECK(TxtError("block 1 1 1 2 2 2\n") ==
        "maps/test.txt:1: boundary: no 'boundary' line in the file");
  CHECK(TxtError("boundary 0 0 0 1 1 1\nboundary 0 0 0 1 1 1\n") ==
        "maps/test.txt:2: boundary: given twice (first at line 1)");
  CHECK(TxtError("boundary 0 0 0 1 1 1\nblock 0 0 0 1 1 1 300 0 0\n")
            .find(":2: block: colour 300 0 0 is outside 0-255") != std::string::npos);
  CHECK(TxtError("boundary 0 0 0 1 1 1\nblock 0 0 0 1 1 1 -1 0 0\n").find(":2:") !=
        std::string::npos);
  CHECK(TxtError(std::string("boundary 0 0 0 1 1 1\n\x01\x02\xff\x00junk", 29)).find(":2:") !=
        std::string::npos);
}

TEST_CASE("RBE595 start and goal files") {
  std::istringstream in("# map2\n\nstart:  (0,20,2)\ngoal: (10, 20, 3)");
  const StartGoal sg = ReadStartGoal(in, "map2.startgoal.txt");
  CHECK(sg.start.isApprox(Vec3(0, 20, 2)));
  CHECK(sg.goal.isApprox(Vec3(10, 20, 3)));

  const auto error = [](const std::string& text) -> std::string {
    std::istringstream bad(text);
    try {
      ReadStartGoal(bad, "sg.txt");
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  CHECK(error("start: (0, 1)\ngoal: (1,2,3)") == "sg.txt:1: start: expected 3 numbers, found 2");
  CHECK(error("start: (0, 1, x)\ngoal: (1,2,3)") == "sg.txt:1: start[2]: 'x' is not a number");
  CHECK(error("start: (0, 1, 2)\n") == "sg.txt: goal: no 'goal:' line");
  CHECK(error("begin: (0, 1, 2)\n").rfind("sg.txt:1: key:", 0) == 0);
  CHECK(error("start: (0,1,2)\nstart: (0,1,2)\ngoal: (1,2,3)") == "sg.txt:2: start: given twice");
}

}  // namespace aerobox
