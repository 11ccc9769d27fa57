// The parameter schema: a struct's Describe is the one place of its keys, ranges and words; the
// range check, the key reference and the readers all come from it.
#include <doctest/doctest.h>

#include <array>
#include <stdexcept>

#include "common/schema.h"

namespace aerobox {
namespace {

struct Example {
  enum class Mode { kSlow, kFast };
  double speed = 2.0;  // [m/s]
  long count = 3;
  int attempts = 5;
  bool loud = false;
  Mode mode = Mode::kSlow;
  double angle = 0.5;                                            // [rad], given in degrees
  Vec3 wind = Vec3(1, 0, 0.5);                                   // [m/s]
  std::array<Vec3, 2> corners = {Vec3(0, 0, 0), Vec3(1, 2, 3)};  // [m]
  std::array<int, 2> turns = {1, -1};

  void Describe(Archive& a) {
    a.Number({"speed", "m/s", "how fast"}, &speed, 0.1, 8);
    a.Integer({"count", "", "how many"}, &count, 0, 10);
    a.Integer({"attempts", "", "how often"}, &attempts, 1, 9);
    a.Boolean({"loud", "", "whether it speaks"}, &loud);
    a.Enum({"mode", "", "which way"}, &mode, {{Mode::kSlow, "slow"}, {Mode::kFast, "fast"}});
    a.Degrees({"angle", "deg", "how far it turns"}, &angle, 1, 90);
    a.Vector({"wind", "m/s", "which way it blows"}, &wind, -5, 5);
    a.Points({"corners", "m", "where it turns"}, corners.data(), 2, -4, 4);
    a.Signs({"turns", "", "which way it turns"}, turns.data(), 2);
  }
};

TEST_CASE("the range check and the key reference come from Describe") {
  Example e;
  CHECK_NOTHROW(ValidateFields(e, "example"));
  e.speed = 9;
  CHECK_THROWS_WITH_AS(ValidateFields(e, "example"), "example.speed out of range: 9",
                       std::invalid_argument);
  e.speed = 2;
  e.attempts = 0;
  CHECK_THROWS_WITH_AS(ValidateFields(e, "example"), "example.attempts out of range: 0",
                       std::invalid_argument);
  e.attempts = 5;
  e.angle = 2.0;  // 115 degrees
  CHECK_THROWS_AS(ValidateFields(e, "example"), std::invalid_argument);
  e.angle = 0.5;
  e.wind.z() = 6;
  CHECK_THROWS_WITH_AS(ValidateFields(e, "example"), "example.wind[2] out of range: 6",
                       std::invalid_argument);

  e.wind.z() = 0.5;
  e.corners[1].y() = -4.5;
  CHECK_THROWS_WITH_AS(ValidateFields(e, "example"), "example.corners[1][1] out of range: -4.5",
                       std::invalid_argument);
  e.corners[1].y() = 2;
  e.turns[0] = 0;
  CHECK_THROWS_WITH_AS(ValidateFields(e, "example"), "example.turns[0] is not 1 or -1: 0",
                       std::invalid_argument);
  e.turns[0] = 1;
  CHECK_NOTHROW(ValidateFields(e, "example"));

  const std::vector<KeyRow> rows = KeyRows<Example>("example");
  REQUIRE(rows.size() == 9);
  CHECK(rows[0].key == "example.speed");
  CHECK(rows[0].unit == "m/s");
  CHECK(rows[0].value == "2");
  CHECK(rows[0].range == "0.1 to 8");
  CHECK(rows[3].range == "true or false");
  CHECK(rows[4].value == "\"slow\"");
  CHECK(rows[4].range == "\"slow\" or \"fast\"");
  CHECK(rows[5].unit == "deg");
  CHECK(rows[6].value == "[1, 0, 0.5]");
  CHECK(rows[6].range == "each -5 to 5");
  CHECK(rows[7].value == "[[0, 0, 0], [1, 2, 3]]");
  CHECK(rows[7].range == "2 points, each coordinate -4 to 4");
  CHECK(rows[8].value == "[1, -1]");
  CHECK(rows[8].range == "2 signs, 1 or -1");
}

TEST_CASE("a default in degrees survives the round trip bit for bit") {
  // an archive that sets nothing: the radians stay exactly what they were
  Example e;
  e.angle = 1.5184;
  CHECK_NOTHROW(ValidateFields(e, "example"));
  CHECK(e.angle == 1.5184);
}

TEST_CASE("a misspelt name finds the name it looks like, and a different one finds none") {
  const std::vector<std::string> names = {"horizon", "iterations", "time_budget"};
  CHECK(NearestName("time_budjet", names) == "time_budget");
  CHECK(NearestName("iteration", names) == "iterations");
  CHECK(NearestName("lookahead", names).empty());
  CHECK(NearestName("x", names).empty());
  CHECK(ListOfNames({"a", "b", "c"}) == "a, b or c");
  CHECK(ListOfNames({"a"}) == "a");
}

}  // namespace
}  // namespace aerobox
