// telemetry.csv's table: the header and one row per control step (columns and units in
// README.md).
#pragma once

#include "mission/flight.h"
#include "telemetry/csv_table.h"

namespace aerobox {

CsvTable TelemetryTable();
void AddTelemetryRow(const TelemetrySample& sample, CsvTable* table);

}  // namespace aerobox
