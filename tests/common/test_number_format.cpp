#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "common/number_format.h"

namespace aerobox {

TEST_CASE("FormatNumber writes the shortest text that reads back to the same double") {
  CHECK(FormatNumber(0.1) == "0.1");
  CHECK(FormatNumber(2.0) == "2");
  CHECK(FormatNumber(-4.3) == "-4.3");
  CHECK(FormatNumber(-0.0) == "0");
  for (const double value : {0.1 + 0.2, 1.0 / 3.0, 6.02214076e23, 1e-300, -7.1e-5}) {
    double back = 0.0;
    REQUIRE(ParseNumber(FormatNumber(value), &back));
    CHECK(back == value);  // exact: shortest round-trip text is the point of the function
  }
  CHECK(FormatVector(Vec3(1, 2.5, 0), ",") == "1,2.5,0");
}

TEST_CASE("ParseNumber takes whole tokens only") {
  double value = 0.0;
  CHECK(ParseNumber("255.000000", &value));
  CHECK(value == 255.0);
  CHECK(ParseNumber("+3", &value));
  CHECK(value == 3.0);
  CHECK(ParseNumber("-1e-3", &value));
  CHECK(value == -1e-3);
  CHECK(ParseNumber("inf", &value));
  CHECK(std::isinf(value));
  for (const char* bad : {"", "+", "abc", "1.0x", "1,5", " 1", "++1", "+-1", "0x10", "1e999"}) {
    CAPTURE(bad);
    CHECK_FALSE(ParseNumber(bad, &value));
  }
}

}  // namespace aerobox
