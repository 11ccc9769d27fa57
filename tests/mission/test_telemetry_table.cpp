// telemetry.csv's schema: one set of columns per controller and extras, and a row that does not
// fit them is refused with the controller's columns named, not written misaligned.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include "control/controllers.h"
#include "mission/telemetry_table.h"

namespace aerobox {

TEST_CASE("the telemetry schema takes the flying controller's own columns") {
  const std::unique_ptr<Controller> cascade = MakeController(ControllerConfig(), QuadParams());
  const TelemetrySchema schema(*cascade, TelemetryExtras{false, false, true, false});
  const std::vector<std::string>& columns = schema.columns();
  REQUIRE(columns.size() == 40 + 6 + 1);
  CHECK(columns[0] == "t");
  CHECK(columns[40] == "vx_sp");  // the cascade's own, after the fixed ones
  CHECK(columns.back() == "goal_index");

  TelemetrySample sample;
  sample.report.assign(6, 0.5);
  CsvTable table = schema.Table();
  schema.AddRow(sample, &table);
  CHECK(table.rows() == 1);

  // a sample from another controller (no columns of its own) does not fit
  sample.report.clear();
  CHECK_THROWS_WITH_AS(schema.AddRow(sample, &table),
                       "telemetry: the controller reported 0 values for the 6 columns of the "
                       "table's controller ( vx_sp vy_sp vz_sp ax_sp ay_sp az_sp )",
                       std::logic_error);
  // and a table made without them refuses the cascade's samples
  sample.report.assign(6, 0.5);
  const TelemetrySchema bare;
  CsvTable other = bare.Table();
  CHECK_THROWS_AS(bare.AddRow(sample, &other), std::logic_error);
}

TEST_CASE("a depth camera's flight has the occupancy map's size in telemetry") {
  const std::unique_ptr<Controller> cascade = MakeController(ControllerConfig(), QuadParams());
  const TelemetrySchema schema(*cascade, TelemetryExtras{false, false, false, true, true});
  const std::vector<std::string>& columns = schema.columns();
  REQUIRE(columns.size() >= 3);
  CHECK(columns[columns.size() - 3] == "replans");
  CHECK(columns[columns.size() - 2] == "map_occupied");
  CHECK(columns.back() == "map_free");
  TelemetrySample sample;
  sample.report.assign(6, 0.0);
  sample.map = {12, 345};
  CsvTable table = schema.Table();
  schema.AddRow(sample, &table);
  const std::string& text = table.Text();
  CHECK(text.substr(text.rfind(",", text.size() - 6)) == ",12,345\n");
}

TEST_CASE("each telemetry quantity is written once, for the CSV and for run()'s result alike") {
  std::set<std::string> columns, keys;
  for (const TelemetryQuantity& q : TelemetryQuantities()) {
    CAPTURE(q.key == nullptr ? q.columns.front() : q.key);
    // as many columns as numbers, or none (in the result only); in one place or the other
    CHECK((q.columns.empty() || static_cast<int>(q.columns.size()) == std::max(1, q.width)));
    CHECK((!q.columns.empty() || q.key != nullptr));
    CHECK((!q.quaternion || q.width == 4));
    for (const char* column : q.columns) CHECK(columns.insert(column).second);
    if (q.key != nullptr) CHECK(keys.insert(std::string(q.group) + "." + q.key).second);
  }
  // the sample's numbers land in their own columns, in the table's order
  TelemetrySample sample;
  sample.t = 1.5;
  sample.state.q_WB = Quat(0.5, 0.5, -0.5, 0.5);
  sample.clearance = std::numeric_limits<double>::infinity();
  sample.wind_W = Vec3(1, 2, 3);
  EstimateSample e;
  e.nees = 7;
  e.pose = PoseMeasurement();
  e.pose->p_W = Vec3(4, 5, 6);
  sample.estimate = e;
  const TelemetrySchema all({}, TelemetryExtras{true, true, true, true});
  const Eigen::VectorXd row = all.Row(sample);
  CHECK(row[all.Index("t")] == 1.5);
  CHECK(row[all.Index("qy")] == -0.5);
  CHECK(std::isinf(row[all.Index("clearance")]));
  CHECK(row[all.Index("wind_z")] == 3);
  CHECK(row[all.Index("est_nees")] == 7);
  CHECK(row[all.Index("meas_y")] == 5);
  CHECK(all.columns().back() == "meas_z");
  CsvTable table = all.Table();
  all.AddRow(sample, &table);  // a clearance with nothing in range is -1 in the CSV
  CHECK(table.rows() == 1);
}

}  // namespace aerobox
