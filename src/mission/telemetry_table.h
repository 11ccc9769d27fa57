// telemetry.csv's table: the header and one row per control step (columns and units in
// README.md), then the controller's own columns.
#pragma once

#include <string>
#include <vector>

#include "mission/flight.h"
#include "mission/setup.h"
#include "telemetry/csv_table.h"

namespace aerobox {

// Columns that only a flight with wind or drag (`air`), or with sensors, has; without them the
// table is the ideal flight's.
struct TelemetryExtras {
  bool air = false;      // wind_x..z [m/s], drag_x..z [N]
  bool sensors = false;  // est_*, imu_*, meas_* (README: telemetry columns)
  bool goals = false;    // goal_index: a mission through several goals
  bool replans = false;  // replans: unknown boxes, replanned around in flight
};
TelemetryExtras TelemetryExtrasFor(const FlightSetup& setup);

// `controller_columns`: Controller::ReportColumns() of the controller that flies; they come
// after the fixed columns and before the extras.
CsvTable TelemetryTable(const std::vector<std::string>& controller_columns = {},
                        const TelemetryExtras& extras = {});
void AddTelemetryRow(const TelemetrySample& sample, CsvTable* table,
                     const TelemetryExtras& extras = {});

}  // namespace aerobox
