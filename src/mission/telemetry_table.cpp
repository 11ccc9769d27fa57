#include "mission/telemetry_table.h"

#include <cmath>

namespace aerobox {
namespace {

constexpr int kFixedColumns = 40;

}  // namespace

CsvTable TelemetryTable(const std::vector<std::string>& controller_columns) {
  std::vector<std::string> columns = {
      "t",     "x",      "y",      "z",       "vx",         "vy",     "vz",     "qw",
      "qx",    "qy",     "qz",     "wx",      "wy",         "wz",     "x_des",  "y_des",
      "z_des", "vx_des", "vy_des", "vz_des",  "ax_des",     "ay_des", "az_des", "f1",
      "f2",    "f3",     "f4",     "pos_err", "thrust_cmd", "wx_sp",  "wy_sp",  "wz_sp",
      "tau_x", "tau_y",  "tau_z",  "f1_cmd",  "f2_cmd",     "f3_cmd", "f4_cmd", "clearance"};
  columns.insert(columns.end(), controller_columns.begin(), controller_columns.end());
  return CsvTable(columns);
}

void AddTelemetryRow(const TelemetrySample& s, CsvTable* table) {
  Eigen::VectorXd row(kFixedColumns + static_cast<int>(s.report.size()));
  const Quat& q = s.state.q_WB;
  row.head<kFixedColumns>() << s.t, s.state.p_W, s.state.v_W, q.w(), q.x(), q.y(), q.z(),
      s.state.w_B, s.setpoint.p_W, s.setpoint.v_W, s.setpoint.a_W, s.rotor_thrusts,
      s.position_error, s.inner.thrust, s.inner.rate_setpoint_B, s.inner.moment_B,
      s.inner.mixer.thrusts, std::isfinite(s.clearance) ? s.clearance : -1.0;
  for (size_t i = 0; i < s.report.size(); ++i)
    row[kFixedColumns + static_cast<int>(i)] = s.report[i];
  table->AddRow(row);
}

}  // namespace aerobox
