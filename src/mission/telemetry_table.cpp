#include "mission/telemetry_table.h"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace aerobox {
namespace {

constexpr int kFixedColumns = 40;
constexpr int kAirColumns = 6;
constexpr int kSensorColumns = 22;

}  // namespace

TelemetryExtras TelemetryExtrasFor(const FlightSetup& setup) {
  return {setup.wind.Enabled() || setup.aero.Enabled(), setup.sensors.Enabled(), !setup.via.empty(),
          setup.HasUnknown()};
}

TelemetrySchema::TelemetrySchema(const Controller& controller, const TelemetryExtras& extras)
    : TelemetrySchema(controller.ReportColumns(), extras) {}

TelemetrySchema::TelemetrySchema(std::vector<std::string> controller_columns,
                                 const TelemetryExtras& extras)
    : controller_columns_(std::move(controller_columns)), extras_(extras) {
  std::vector<std::string>& columns = columns_;
  columns = {"t",     "x",      "y",      "z",       "vx",         "vy",     "vz",     "qw",
             "qx",    "qy",     "qz",     "wx",      "wy",         "wz",     "x_des",  "y_des",
             "z_des", "vx_des", "vy_des", "vz_des",  "ax_des",     "ay_des", "az_des", "f1",
             "f2",    "f3",     "f4",     "pos_err", "thrust_cmd", "wx_sp",  "wy_sp",  "wz_sp",
             "tau_x", "tau_y",  "tau_z",  "f1_cmd",  "f2_cmd",     "f3_cmd", "f4_cmd", "clearance"};
  columns.insert(columns.end(), controller_columns_.begin(), controller_columns_.end());
  if (extras.goals) columns.push_back("goal_index");
  if (extras.replans) columns.push_back("replans");
  if (extras.air) {
    columns.insert(columns.end(), {"wind_x", "wind_y", "wind_z", "drag_x", "drag_y", "drag_z"});
  }
  if (extras.sensors) {
    columns.insert(
        columns.end(),
        {"est_x",  "est_y",  "est_z",   "est_vx",      "est_vy",   "est_vz", "est_qw", "est_qx",
         "est_qy", "est_qz", "est_err", "est_att_err", "est_nees", "imu_gx", "imu_gy", "imu_gz",
         "imu_ax", "imu_ay", "imu_az",  "meas_x",      "meas_y",   "meas_z"});
  }
}

int TelemetrySchema::Index(const std::string& name) const {
  for (size_t i = 0; i < columns_.size(); ++i) {
    if (columns_[i] == name) return static_cast<int>(i);
  }
  throw std::logic_error("telemetry: no column " + name);
}

void TelemetrySchema::AddRow(const TelemetrySample& sample, CsvTable* table) const {
  Eigen::VectorXd row = Row(sample);
  double& clearance = row[kFixedColumns - 1];
  if (!std::isfinite(clearance)) clearance = -1.0;
  table->AddRow(row);
}

Eigen::VectorXd TelemetrySchema::Row(const TelemetrySample& s) const {
  const int controller = static_cast<int>(controller_columns_.size());
  if (s.report.size() != controller_columns_.size()) {
    std::string names;
    for (const std::string& name : controller_columns_) names += " " + name;
    throw std::logic_error("telemetry: the controller reported " + std::to_string(s.report.size()) +
                           " values for the " + std::to_string(controller) +
                           " columns of the table's controller (" +
                           (names.empty() ? " none" : names) + " )");
  }
  const TelemetryExtras& extras = extras_;
  Eigen::VectorXd row(static_cast<Eigen::Index>(columns_.size()));
  const Quat& q = s.state.q_WB;
  row.head<kFixedColumns>() << s.t, s.state.p_W, s.state.v_W, q.w(), q.x(), q.y(), q.z(),
      s.state.w_B, s.setpoint.p_W, s.setpoint.v_W, s.setpoint.a_W, s.rotor_thrusts,
      s.position_error, s.inner.thrust, s.inner.rate_setpoint_B, s.inner.moment_B,
      s.inner.mixer.thrusts, s.clearance;
  for (int i = 0; i < controller; ++i) row[kFixedColumns + i] = s.report[i];
  int at = kFixedColumns + controller;
  if (extras.goals) row[at++] = s.goal_index;
  if (extras.replans) row[at++] = s.replans;
  if (extras.air) {
    row.segment<kAirColumns>(at) << s.wind_W, s.aero_force_W;
    at += kAirColumns;
  }
  if (extras.sensors) {
    const EstimateSample e = s.estimate.value_or(EstimateSample());
    const Quat& qe = e.estimate.q_WB;
    // before the first measurement arrives, the estimate's own position stands in
    const Vec3 measured = e.pose ? e.pose->p_W : e.estimate.p_W;
    row.segment<kSensorColumns>(at) << e.estimate.p_W, e.estimate.v_W, qe.w(), qe.x(), qe.y(),
        qe.z(), e.error.head<3>().norm(), e.error.segment<3>(6).norm(), e.nees, e.imu.gyro_B,
        e.imu.accel_B, measured;
  }
  return row;
}

}  // namespace aerobox
