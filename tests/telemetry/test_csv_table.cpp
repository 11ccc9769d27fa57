#include <doctest/doctest.h>

#include <stdexcept>

#include "telemetry/csv_table.h"

namespace aerobox {

TEST_CASE("CSV text: header, shortest numbers, fixed column count") {
  CsvTable table({"t", "x"});
  table.AddRow({0.0, 0.1});
  table.AddRow(Eigen::Vector2d(1e-3, -2.5));
  CHECK(table.Text() == "t,x\n0,0.1\n0.001,-2.5\n");
  CHECK(table.rows() == 2);
  CHECK_THROWS_AS(table.AddRow({1.0}), std::invalid_argument);
  CHECK_THROWS_AS(CsvTable({"a,b"}), std::invalid_argument);
  // shortest round-trip text: 1e9 is "1e+09"
  CHECK(PathCsv({Vec3(1, 2, 3), Vec3(0.5, -1, 1e9)}) == "x,y,z\n1,2,3\n0.5,-1,1e+09\n");
}

}  // namespace aerobox

#include <limits>

#include "telemetry/json_object.h"

namespace aerobox {

TEST_CASE("JSON summaries: order kept, numbers exact, strings escaped, no NaN") {
  JsonObject inner;
  inner.Add("mujoco", "2.2.2");
  JsonObject summary;
  summary.Add("status", "reached \"goal\"").Add("seed", 7).Add("rms", 0.1);
  summary.Add("none", std::numeric_limits<double>::infinity());
  summary.Add("ok", true).Add("versions", inner);
  CHECK(
      summary.Text() ==
      "{\n  \"status\": \"reached \\\"goal\\\"\",\n  \"seed\": 7,\n  \"rms\": 0.1,\n"
      "  \"none\": null,\n  \"ok\": true,\n  \"versions\": {\n    \"mujoco\": \"2.2.2\"\n  }\n}\n");
}

}  // namespace aerobox
