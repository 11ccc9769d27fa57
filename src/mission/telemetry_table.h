// telemetry.csv's table: the header and one row per control step (columns and units in
// README.md), then the controller's own columns.
#pragma once

#include <string>
#include <vector>

#include "mission/flight.h"
#include "telemetry/csv_table.h"

namespace aerobox {

// `controller_columns`: Controller::ReportColumns() of the controller that flies.
CsvTable TelemetryTable(const std::vector<std::string>& controller_columns = {});
void AddTelemetryRow(const TelemetrySample& sample, CsvTable* table);

}  // namespace aerobox
