// The telemetry's columns, once (TelemetryQuantities): the fixed ones (docs/outputs.md), the
// controller's own (Controller::ReportColumns), then the extras a flight has. telemetry.csv, the
// Python result of run(), the outputs written after a Python run, report.html and the
// benchmarks all take their columns and rows from here, so that they cannot disagree.
#pragma once

#include <string>
#include <vector>

#include "control/controller.h"
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
  bool map = false;      // map_occupied, map_free: the depth camera's occupancy map
};
TelemetryExtras TelemetryExtrasFor(const FlightSetup& setup);

// Which flights have a quantity in telemetry.csv: every flight, or one with the extra.
enum class TelemetryPart { kEvery, kGoals, kReplans, kMap, kAir, kSensors };

// One quantity of the telemetry, once: its columns in telemetry.csv and its array in the
// Python result of run() (Simulator.run's doc), and how a sample gives its numbers.
struct TelemetryQuantity {
  TelemetryPart part;
  std::vector<const char*> columns;  // telemetry.csv's, in order; none: only in the result
  const char* group;                 // run()'s sub-dict ("state", "flat"; "": the top level)
  const char* key;                   // its key there; nullptr: only in telemetry.csv
  int width;                         // numbers per sample (0: one, a 1-D array in the result)
  // A quaternion: given w first (telemetry.csv's order); the result has RotorPy's x, y, z, w.
  bool quaternion;
  void (*fill)(const TelemetrySample& sample, double* out);
};
// Every quantity, in telemetry.csv's order within each part; the controller's own columns
// (Controller::ReportColumns) come after the kEvery part. A quantity in the result is there for
// every flight, but kSensors' only when every sample has the estimate.
const std::vector<TelemetryQuantity>& TelemetryQuantities();

class TelemetrySchema {
 public:
  // The columns of a flight of `controller` with `extras`.
  TelemetrySchema(const Controller& controller, const TelemetryExtras& extras);
  // ... of a controller whose own columns are `controller_columns`.
  explicit TelemetrySchema(std::vector<std::string> controller_columns = {},
                           const TelemetryExtras& extras = {});

  const std::vector<std::string>& columns() const { return columns_; }
  const std::vector<std::string>& controller_columns() const { return controller_columns_; }
  // Where the column `name` is; throws std::logic_error when the table has no such column.
  int Index(const std::string& name) const;
  // An empty table with these columns.
  CsvTable Table() const { return CsvTable(columns_); }
  // The values of `sample`, one per column, as flown: a clearance with no obstacle in range is
  // not finite. Throws std::logic_error naming the controller's columns when the sample's
  // report has another number of values (a table made for another controller).
  Eigen::VectorXd Row(const TelemetrySample& sample) const;
  // Row(sample) added to `table`, where a clearance with no obstacle in range is -1.
  void AddRow(const TelemetrySample& sample, CsvTable* table) const;

 private:
  std::vector<std::string> controller_columns_;
  std::vector<TelemetryPart> parts_;  // the extras', in the table's order
  std::vector<std::string> columns_;
  int clearance_ = 0;  // the clearance column's index
};

}  // namespace aerobox
