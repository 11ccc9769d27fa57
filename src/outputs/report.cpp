#include "outputs/report.h"

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "outputs/files.h"
#include "perception/occupancy_grid.h"

namespace aerobox {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// report_page.html, built in by CMake (aerobox_embed_page)
const std::string& ReportPageTemplate();

namespace {

constexpr double kSamplePeriod = 0.01;  // [s]: the page's telemetry, at most 100 rows a second
constexpr double kMapPeriod = 1.0;      // [s]: the occupancy map's snapshots

// The telemetry.csv columns the page shows (TelemetrySchema's names), and those of a flight in
// wind or drag.
const char* const kPageColumns[] = {"t",         "x",  "y",  "z",  "x_des",  "y_des",
                                    "z_des",     "vx", "vy", "vz", "vx_des", "vy_des",
                                    "vz_des",    "qw", "qx", "qy", "qz",     "pos_err",
                                    "clearance", "f1", "f2", "f3", "f4"};
const char* const kAirColumns[] = {"wind_x", "wind_y", "wind_z"};

// A number with `digits` decimals, or null when it is not finite.
Json Number(double value, int digits = 4) {
  if (!std::isfinite(value)) return nullptr;
  const double scale = std::pow(10.0, digits);
  const double rounded = std::round(value * scale) / scale;
  return rounded == 0.0 ? 0.0 : rounded;  // never -0
}

Json Point(const Vec3& p, int digits = 4) {
  return Json::array({Number(p.x(), digits), Number(p.y(), digits), Number(p.z(), digits)});
}

Json Points(const std::vector<Vec3>& points, int digits = 4) {
  Json array = Json::array();
  for (const Vec3& p : points) array.push_back(Point(p, digits));
  return array;
}

Json Numbers(const std::vector<double>& values, int digits) {
  Json array = Json::array();
  for (const double v : values) array.push_back(Number(v, digits));
  return array;
}

// The planned trajectory every 50 ms: positions and speeds.
Json TrajectoryData(const PlanOutcome& plan) {
  Json p = Json::array();
  std::vector<double> speeds;
  if (plan.trajectory && plan.trajectory->status == TrajectoryStatus::kSolved) {
    const PiecewiseTrajectory& t = plan.trajectory->trajectory;
    for (double s = 0; s <= t.duration() + 1e-9; s += 0.05) {
      p.push_back(Point(t.Evaluate(s, kPosition)));
      speeds.push_back(t.Evaluate(s, kVelocity).norm());
    }
  }
  return {{"p", p}, {"speed", Numbers(speeds, 3)}};
}

Json Boxes(const FlightSetup& setup, const std::vector<double>& revealed_at) {
  Json boxes = Json::array();
  for (size_t i = 0; i < setup.map.boxes.size(); ++i) {
    const Box& box = setup.map.boxes[i];
    Json item = {{"name", box.name},
                 {"min", Point(box.extent.min)},
                 {"max", Point(box.extent.max)},
                 {"rgb", Point(box.rgb, 3)}};
    if (i < setup.unknown.size() && setup.unknown[i]) {
      // when the sensor revealed it [s] (-1: never)
      item["revealed"] = Number(i < revealed_at.size() ? revealed_at[i] : -1.0, 3);
    }
    boxes.push_back(item);
  }
  return boxes;
}

// The occupancy map's snapshots: {resolution, [{t, boxes: [[min x, y, z, max x, y, z], ...]}]}
// (null without a depth camera).
Json OccupancySnapshots(const std::vector<std::pair<double, std::vector<Aabb>>>& snapshots,
                        double resolution) {
  if (snapshots.empty()) return nullptr;
  Json list = Json::array();
  for (const auto& [t, boxes] : snapshots) {
    Json flat = Json::array();
    for (const Aabb& b : boxes) {
      flat.push_back(
          Json::array({Number(b.min.x(), 3), Number(b.min.y(), 3), Number(b.min.z(), 3),
                       Number(b.max.x(), 3), Number(b.max.y(), 3), Number(b.max.z(), 3)}));
    }
    list.push_back({{"t", Number(t, 3)}, {"boxes", flat}});
  }
  return {{"resolution", Number(resolution, 3)}, {"snapshots", list}};
}

Json Replans(const std::vector<ReplanEvent>& replans) {
  Json array = Json::array();
  for (const ReplanEvent& r : replans) {
    array.push_back({{"t", Number(r.t, 3)},
                     {"trigger", r.trigger},
                     {"outcome", r.outcome},
                     {"abandoned", Points(r.abandoned, 3)},
                     {"replacement", Points(r.replacement, 3)},
                     {"speeds", Numbers(r.replacement_speeds, 3)}});
  }
  return array;
}

}  // namespace

ReportOutputs::ReportOutputs(std::string folder, const FlightSetup& setup)
    : folder_(std::move(folder)), setup_(setup) {}

void ReportOutputs::OnPlan(const PlanOutcome& plan) {
  Json via = Json::array();
  for (const auto& v : plan.via) via.push_back(Point(v.used));
  const Json data = {{"start", Point(plan.start.used)},
                     {"goal", Point(plan.goal.used)},
                     {"via", via},
                     {"path", Points(plan.result.path)},
                     {"trajectory", TrajectoryData(plan)}};
  plan_json_ = data.dump();
}

void ReportOutputs::OnFlightStart(const Simulation&, const Controller& controller) {
  const TelemetryExtras extras = TelemetryExtrasFor(setup_);
  schema_ = TelemetrySchema(controller, extras);
  column_names_.assign(std::begin(kPageColumns), std::end(kPageColumns));
  if (extras.air)
    column_names_.insert(column_names_.end(), std::begin(kAirColumns), std::end(kAirColumns));
  column_index_.clear();
  for (const std::string& name : column_names_) column_index_.push_back(schema_.Index(name));
  columns_.assign(column_names_.size(), {});
}

void ReportOutputs::OnSample(const TelemetrySample& sample) {
  if (sample.t + 1e-9 < next_sample_) return;
  next_sample_ = sample.t + kSamplePeriod;
  const Eigen::VectorXd row = schema_.Row(sample);
  for (size_t c = 0; c < column_index_.size(); ++c) columns_[c].push_back(row[column_index_[c]]);
}

void ReportOutputs::OnFlightEnd(const Simulation&, const FlightResult& result) {
  flown_ = true;
  result_ = result;
  end_position_ = result.end_position;
}

void ReportOutputs::OnDepthFrame(double t, const DepthImage&, const OccupancyGrid& map) {
  if (!occupied_.empty() && t < occupied_.back().first + kMapPeriod - 1e-9) return;
  occupied_.push_back({t, map.OccupiedBoxes(setup_.sensing.map.columns)});
}

void ReportOutputs::OnDiscovery(const std::vector<double>& revealed_at,
                                const std::vector<ReplanEvent>& replans) {
  revealed_at_ = revealed_at;
  if (replans.size() != replans_.size()) replans_ = replans;
}

std::string ReportOutputs::VehicleJson() const {
  Json failure = nullptr;
  if (flown_ && result_.status != FlightStatus::kReachedGoal) {
    failure = {{"status", ToString(result_.status)},
               {"obstacle", result_.obstacle},
               {"t", Number(result_.time, 3)},
               {"p", Point(end_position_)}};
  }
  Json telemetry = {{"rate", 1.0 / kSamplePeriod}};  // one array per column
  for (size_t c = 0; c < column_names_.size(); ++c) {
    telemetry[column_names_[c]] = Numbers(columns_[c], column_names_[c] == "t" ? 3 : 4);
  }
  const Json data = {
      {"plan", Json::parse(plan_json_)}, {"telemetry", telemetry}, {"failure", failure}};
  return data.dump();
}

namespace {

// The page's data besides the vehicles' own, and the page written from it.
Json PageData(const FlightSetup& setup, const std::string& summary_json, const std::string& command,
              const std::vector<double>& revealed_at, const std::vector<ReplanEvent>& replans,
              const std::vector<std::pair<double, std::vector<Aabb>>>& occupied) {
  const Map& map = setup.map;
  return {{"name", setup.name},
          {"command", command},
          {"summary", Json::parse(summary_json)},
          {"bounds", Json::array({Point(map.bounds.min), Point(map.bounds.max)})},
          {"boxes", Boxes(setup, revealed_at)},
          {"replans", Replans(replans)},
          {"occupancy", OccupancySnapshots(occupied, setup.sensing.map.resolution)},
          {"vehicle",
           {{"size", Point(setup.vehicle.collision_size)},
            {"max_thrust", Number(setup.vehicle.MaxRotorThrust())}}}};
}

std::string WritePage(const std::string& folder, const std::string& title, const Json& data,
                      const ReportScripts& scripts) {
  PageParts parts;
  parts.title = title;
  parts.scripts = {{"/*AEROBOX_THREE*/", ReadPageScript(scripts.three)},
                   {"/*AEROBOX_ORBIT_CONTROLS*/", ReadPageScript(scripts.orbit_controls)},
                   {"/*AEROBOX_CHART*/", ReadPageScript(scripts.chart)}};
  parts.data_json = data.dump(-1, ' ', false, Json::error_handler_t::replace);
  const std::string path = (fs::path(folder) / "report.html").string();
  WriteFileAtomically(path, FillPage(ReportPageTemplate(), parts));
  return path;
}

}  // namespace

std::string ReportOutputs::Write(const std::string& summary_json, const std::string& command,
                                 const ReportScripts& scripts) const {
  Json data = PageData(setup_, summary_json, command, revealed_at_, replans_, occupied_);
  data.update(Json::parse(VehicleJson()));
  return WritePage(folder_, setup_.name, data, scripts);
}

std::string ReportOutputs::WriteSwarm(const std::string& folder, const FlightSetup& setup,
                                      const std::vector<const ReportOutputs*>& vehicles,
                                      const std::vector<std::string>& names,
                                      const std::vector<std::string>& colours,
                                      const std::string& summary_json, const std::string& command,
                                      const ReportScripts& scripts) {
  Json data = PageData(setup, summary_json, command, {}, {}, {});
  Json list = Json::array();
  for (size_t i = 0; i < vehicles.size(); ++i) {
    Json v = Json::parse(vehicles[i]->VehicleJson());
    v["name"] = names.at(i);
    std::istringstream rgba(colours.at(i));
    double r = 0, g = 0, b = 0;
    rgba >> r >> g >> b;
    v["rgb"] = Json::array({r, g, b});
    v["size"] = Point(vehicles[i]->setup_.vehicle.collision_size);
    list.push_back(v);
  }
  if (!list.empty())
    data.update({{"plan", list[0]["plan"]},
                 {"telemetry", list[0]["telemetry"]},
                 {"failure", list[0]["failure"]}});
  data["vehicles"] = list;
  return WritePage(folder, setup.name, data, scripts);
}

}  // namespace aerobox
