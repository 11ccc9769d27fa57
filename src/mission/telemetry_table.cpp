#include "mission/telemetry_table.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace aerobox {
namespace {

void Put(const Vec3& v, double* out) { std::copy(v.data(), v.data() + 3, out); }
void Put(const Vec4& v, double* out) { std::copy(v.data(), v.data() + 4, out); }
void Put(const Quat& q, double* out) {  // w first
  const double wxyz[4] = {q.w(), q.x(), q.y(), q.z()};
  std::copy(wxyz, wxyz + 4, out);
}
// The sensors' sample, or (before the sensors' first sample) zeros.
const EstimateSample& Sensed(const TelemetrySample& s) {
  static const EstimateSample kNone;
  return s.estimate ? *s.estimate : kNone;
}

using Sample = TelemetrySample;
constexpr TelemetryPart kEvery = TelemetryPart::kEvery;
constexpr TelemetryPart kSensors = TelemetryPart::kSensors;

std::vector<TelemetryQuantity> MakeQuantities() {
  return {
      {kEvery, {"t"}, "", "time", 0, false, [](const Sample& s, double* o) { *o = s.t; }},
      {kEvery,
       {"x", "y", "z"},
       "state",
       "x",
       3,
       false,
       [](const Sample& s, double* o) { Put(s.state.p_W, o); }},
      {kEvery,
       {"vx", "vy", "vz"},
       "state",
       "v",
       3,
       false,
       [](const Sample& s, double* o) { Put(s.state.v_W, o); }},
      {kEvery,
       {"qw", "qx", "qy", "qz"},
       "state",
       "q",
       4,
       true,
       [](const Sample& s, double* o) { Put(s.state.q_WB, o); }},
      {kEvery,
       {"wx", "wy", "wz"},
       "state",
       "w",
       3,
       false,
       [](const Sample& s, double* o) { Put(s.state.w_B, o); }},
      {kEvery,
       {"x_des", "y_des", "z_des"},
       "flat",
       "x",
       3,
       false,
       [](const Sample& s, double* o) { Put(s.setpoint.p_W, o); }},
      {kEvery,
       {"vx_des", "vy_des", "vz_des"},
       "flat",
       "x_dot",
       3,
       false,
       [](const Sample& s, double* o) { Put(s.setpoint.v_W, o); }},
      {kEvery,
       {"ax_des", "ay_des", "az_des"},
       "flat",
       "x_ddot",
       3,
       false,
       [](const Sample& s, double* o) { Put(s.setpoint.a_W, o); }},
      {kEvery,
       {"f1", "f2", "f3", "f4"},
       "",
       "rotor_thrusts",
       4,
       false,
       [](const Sample& s, double* o) { Put(s.rotor_thrusts, o); }},
      {kEvery,
       {"pos_err"},
       "",
       "position_error",
       0,
       false,
       [](const Sample& s, double* o) { *o = s.position_error; }},
      {kEvery,
       {"thrust_cmd"},
       "control",
       "cmd_thrust",
       0,
       false,
       [](const Sample& s, double* o) { *o = s.inner.thrust; }},
      {kEvery,
       {"wx_sp", "wy_sp", "wz_sp"},
       "",
       nullptr,
       3,
       false,
       [](const Sample& s, double* o) { Put(s.inner.rate_setpoint_B, o); }},
      {kEvery,
       {"tau_x", "tau_y", "tau_z"},
       "control",
       "cmd_moment",
       3,
       false,
       [](const Sample& s, double* o) { Put(s.inner.moment_B, o); }},
      {kEvery,
       {"f1_cmd", "f2_cmd", "f3_cmd", "f4_cmd"},
       "control",
       "cmd_motor_thrusts",
       4,
       false,
       [](const Sample& s, double* o) { Put(s.inner.mixer.thrusts, o); }},
      {kEvery,
       {"clearance"},
       "",
       "clearance",
       0,
       false,
       [](const Sample& s, double* o) { *o = s.clearance; }},
      // the setpoint's higher derivatives and yaw: RotorPy's flat outputs, in the result only
      {kEvery,
       {},
       "flat",
       "x_dddot",
       3,
       false,
       [](const Sample& s, double* o) { Put(s.setpoint.j_W, o); }},
      {kEvery,
       {},
       "flat",
       "x_ddddot",
       3,
       false,
       [](const Sample& s, double* o) { Put(s.setpoint.s_W, o); }},
      {kEvery,
       {},
       "flat",
       "yaw",
       0,
       false,
       [](const Sample& s, double* o) { *o = s.setpoint.yaw; }},
      {kEvery,
       {},
       "flat",
       "yaw_dot",
       0,
       false,
       [](const Sample& s, double* o) { *o = s.setpoint.yaw_rate; }},
      {TelemetryPart::kGoals,
       {"goal_index"},
       "",
       nullptr,
       0,
       false,
       [](const Sample& s, double* o) { *o = s.goal_index; }},
      {TelemetryPart::kReplans,
       {"replans"},
       "",
       nullptr,
       0,
       false,
       [](const Sample& s, double* o) { *o = s.replans; }},
      {TelemetryPart::kMap,
       {"map_occupied"},
       "",
       "map_occupied",
       0,
       false,
       [](const Sample& s, double* o) { *o = static_cast<double>(s.map.occupied); }},
      {TelemetryPart::kMap,
       {"map_free"},
       "",
       "map_free",
       0,
       false,
       [](const Sample& s, double* o) { *o = static_cast<double>(s.map.free); }},
      {TelemetryPart::kAir,
       {"wind_x", "wind_y", "wind_z"},
       "",
       "wind",
       3,
       false,
       [](const Sample& s, double* o) { Put(s.wind_W, o); }},
      {TelemetryPart::kAir,
       {"drag_x", "drag_y", "drag_z"},
       "",
       "drag",
       3,
       false,
       [](const Sample& s, double* o) { Put(s.aero_force_W, o); }},
      {kSensors,
       {"est_x", "est_y", "est_z"},
       "estimate",
       "x",
       3,
       false,
       [](const Sample& s, double* o) { Put(Sensed(s).estimate.p_W, o); }},
      {kSensors,
       {"est_vx", "est_vy", "est_vz"},
       "estimate",
       "v",
       3,
       false,
       [](const Sample& s, double* o) { Put(Sensed(s).estimate.v_W, o); }},
      {kSensors,
       {"est_qw", "est_qx", "est_qy", "est_qz"},
       "estimate",
       "q",
       4,
       true,
       [](const Sample& s, double* o) { Put(Sensed(s).estimate.q_WB, o); }},
      {kSensors,
       {},
       "estimate",
       "w",
       3,
       false,
       [](const Sample& s, double* o) { Put(Sensed(s).estimate.w_B, o); }},
      {kSensors,
       {"est_err"},
       "",
       "estimate_error",
       0,
       false,
       [](const Sample& s, double* o) { *o = Sensed(s).error.head<3>().norm(); }},
      {kSensors,
       {"est_att_err"},
       "",
       nullptr,
       0,
       false,
       [](const Sample& s, double* o) { *o = Sensed(s).error.segment<3>(6).norm(); }},
      {kSensors,
       {"est_nees"},
       "",
       "nees",
       0,
       false,
       [](const Sample& s, double* o) { *o = Sensed(s).nees; }},
      {kSensors,
       {"imu_gx", "imu_gy", "imu_gz"},
       "imu",
       "gyro",
       3,
       false,
       [](const Sample& s, double* o) { Put(Sensed(s).imu.gyro_B, o); }},
      {kSensors,
       {"imu_ax", "imu_ay", "imu_az"},
       "imu",
       "accel",
       3,
       false,
       [](const Sample& s, double* o) { Put(Sensed(s).imu.accel_B, o); }},
      // before the first measurement arrives, the estimate's own position stands in
      {kSensors,
       {"meas_x", "meas_y", "meas_z"},
       "",
       nullptr,
       3,
       false,
       [](const Sample& s, double* o) {
         const EstimateSample& e = Sensed(s);
         Put(e.pose ? e.pose->p_W : e.estimate.p_W, o);
       }},
  };
}

}  // namespace

const std::vector<TelemetryQuantity>& TelemetryQuantities() {
  static const std::vector<TelemetryQuantity> quantities = MakeQuantities();
  return quantities;
}

TelemetryExtras TelemetryExtrasFor(const FlightSetup& setup) {
  return {setup.wind.Enabled() || setup.aero.Enabled(), setup.sensors.Enabled(), !setup.via.empty(),
          setup.HasUnknown(),
          setup.HasUnknown() && setup.sensing.kind == SensingParams::Kind::kDepth};
}

TelemetrySchema::TelemetrySchema(const Controller& controller, const TelemetryExtras& extras)
    : TelemetrySchema(controller.ReportColumns(), extras) {}

TelemetrySchema::TelemetrySchema(std::vector<std::string> controller_columns,
                                 const TelemetryExtras& extras)
    : controller_columns_(std::move(controller_columns)) {
  const auto add = [this](TelemetryPart part) {
    for (const TelemetryQuantity& q : TelemetryQuantities()) {
      if (q.part == part) columns_.insert(columns_.end(), q.columns.begin(), q.columns.end());
    }
  };
  add(TelemetryPart::kEvery);
  clearance_ = Index("clearance");
  columns_.insert(columns_.end(), controller_columns_.begin(), controller_columns_.end());
  const std::pair<bool, TelemetryPart> extra_parts[] = {{extras.goals, TelemetryPart::kGoals},
                                                        {extras.replans, TelemetryPart::kReplans},
                                                        {extras.map, TelemetryPart::kMap},
                                                        {extras.air, TelemetryPart::kAir},
                                                        {extras.sensors, TelemetryPart::kSensors}};
  for (const auto& [on, part] : extra_parts) {
    if (!on) continue;
    parts_.push_back(part);
    add(part);
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
  double& clearance = row[clearance_];
  if (!std::isfinite(clearance)) clearance = -1.0;
  table->AddRow(row);
}

Eigen::VectorXd TelemetrySchema::Row(const TelemetrySample& s) const {
  if (s.report.size() != controller_columns_.size()) {
    std::string names;
    for (const std::string& name : controller_columns_) names += " " + name;
    throw std::logic_error("telemetry: the controller reported " + std::to_string(s.report.size()) +
                           " values for the " + std::to_string(controller_columns_.size()) +
                           " columns of the table's controller (" +
                           (names.empty() ? " none" : names) + " )");
  }
  Eigen::VectorXd row(static_cast<Eigen::Index>(columns_.size()));
  double* at = row.data();
  const auto fill = [&](TelemetryPart part) {
    for (const TelemetryQuantity& q : TelemetryQuantities()) {
      if (q.part != part || q.columns.empty()) continue;
      q.fill(s, at);
      at += q.columns.size();
    }
  };
  fill(TelemetryPart::kEvery);
  at = std::copy(s.report.begin(), s.report.end(), at);
  for (TelemetryPart part : parts_) fill(part);
  return row;
}

}  // namespace aerobox
