// aerobox fly: plan, solve, fly in MuJoCo, and write the flight's files.
#pragma once

#include <ostream>
#include <string>

#include "app/flight.h"
#include "app/scenario.h"
#include "telemetry/csv_table.h"

namespace aerobox {

struct FlyOptions {
  std::string out_dir;  // "" : renders/<scenario name>/
  bool video = true;
};

// Runs the whole job and returns the exit code (app/exit_codes.h). Throws InputError for bad
// input, before anything is written.
int RunFly(const FlightSetup& setup, const FlyOptions& options, std::ostream& out,
           std::ostream& err);

// telemetry.csv: the header and one row per control step (units in README.md).
CsvTable TelemetryTable();
void AddTelemetryRow(const TelemetrySample& sample, CsvTable* table);

}  // namespace aerobox
