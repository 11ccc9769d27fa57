// telemetry.csv's schema: one set of columns per controller and extras, and a row that does not
// fit them is refused with the controller's columns named, not written misaligned.
#include <doctest/doctest.h>

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

}  // namespace aerobox
