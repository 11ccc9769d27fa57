#include "mission/telemetry_table.h"

#include <cmath>

namespace aerobox {

CsvTable TelemetryTable() {
  return CsvTable({"t",          "x",      "y",      "z",      "vx",       "vy",     "vz",
                   "qw",         "qx",     "qy",     "qz",     "wx",       "wy",     "wz",
                   "x_des",      "y_des",  "z_des",  "vx_des", "vy_des",   "vz_des", "ax_des",
                   "ay_des",     "az_des", "f1",     "f2",     "f3",       "f4",     "pos_err",
                   "thrust_cmd", "wx_sp",  "wy_sp",  "wz_sp",  "tau_x",    "tau_y",  "tau_z",
                   "f1_cmd",     "f2_cmd", "f3_cmd", "f4_cmd", "clearance"});
}

void AddTelemetryRow(const TelemetrySample& s, CsvTable* table) {
  Eigen::VectorXd row(40);
  const Quat& q = s.state.q_WB;
  row << s.t, s.state.p_W, s.state.v_W, q.w(), q.x(), q.y(), q.z(), s.state.w_B, s.setpoint.p_W,
      s.setpoint.v_W, s.setpoint.a_W, s.rotor_thrusts, s.position_error, s.control.attitude.thrust,
      s.control.rate_setpoint_B, s.control.torque_B, s.control.mixer.thrusts,
      std::isfinite(s.clearance) ? s.clearance : -1.0;
  table->AddRow(row);
}

}  // namespace aerobox
