#include "outputs/report.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "common/quoting.h"
#include "outputs/files.h"
#include "outputs/report_page.h"

namespace aerobox {
namespace fs = std::filesystem;
namespace {

constexpr double kSamplePeriod = 0.01;  // [s]: the page's telemetry, at most 100 rows a second

// Compact JSON numbers: `digits` decimals, trailing zeros dropped; null when not finite.
class Numbers {
 public:
  explicit Numbers(std::ostringstream& out) : out_(out) {}
  void Number(double value, int digits = 4) {
    if (!std::isfinite(value)) {
      out_ << "null";
      return;
    }
    char text[48];
    std::snprintf(text, sizeof(text), "%.*f", digits, value);
    std::string shown = text;
    if (shown.find('.') != std::string::npos) {
      while (shown.back() == '0') shown.pop_back();
      if (shown.back() == '.') shown.pop_back();
    }
    if (shown == "-0") shown = "0";
    out_ << shown;
  }
  void Point(const Vec3& p, int digits = 4) {
    out_ << "[";
    for (int i = 0; i < 3; ++i) {
      if (i) out_ << ",";
      Number(p[i], digits);
    }
    out_ << "]";
  }
  void Points(const std::vector<Vec3>& points, int digits = 4) {
    out_ << "[";
    for (size_t i = 0; i < points.size(); ++i) {
      if (i) out_ << ",";
      Point(points[i], digits);
    }
    out_ << "]";
  }

 private:
  std::ostringstream& out_;
};

std::string Script(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in || text.str().empty()) {
    throw InputError({path, 0}, "report.html",
                     "the page's script is missing: install libjs-three and libjs-chart.js "
                     "(tools/setup.sh), or leave the page out with --no-report");
  }
  return text.str();
}

void Replace(std::string* text, const std::string& marker, const std::string& with) {
  const size_t at = text->find(marker);
  if (at == std::string::npos) throw std::logic_error("report page: no " + marker);
  text->replace(at, marker.size(), with);
}

}  // namespace

ReportOutputs::ReportOutputs(std::string folder, const FlightSetup& setup)
    : folder_(std::move(folder)), setup_(setup) {}

void ReportOutputs::OnPlan(const PlanOutcome& plan) {
  std::ostringstream out;
  Numbers n(out);
  out << "{\"start\":";
  n.Point(plan.start.used);
  out << ",\"goal\":";
  n.Point(plan.goal.used);
  out << ",\"via\":[";
  for (size_t i = 0; i < plan.via.size(); ++i) {
    if (i) out << ",";
    n.Point(plan.via[i].used);
  }
  out << "],\"path\":";
  n.Points(plan.result.path);
  out << ",\"trajectory\":{\"p\":[";
  std::vector<double> speeds;
  if (plan.trajectory && plan.trajectory->status == TrajectoryStatus::kSolved) {
    const PiecewiseTrajectory& t = plan.trajectory->trajectory;
    bool first = true;
    for (double s = 0; s <= t.duration() + 1e-9; s += 0.05) {
      if (!first) out << ",";
      first = false;
      n.Point(t.Evaluate(s, kPosition));
      speeds.push_back(t.Evaluate(s, kVelocity).norm());
    }
  }
  out << "],\"speed\":[";
  for (size_t i = 0; i < speeds.size(); ++i) {
    if (i) out << ",";
    n.Number(speeds[i], 3);
  }
  out << "]}}";
  plan_json_ = out.str();
}

void ReportOutputs::OnSample(const TelemetrySample& sample) {
  if (sample.t + 1e-9 < next_sample_) return;
  next_sample_ = sample.t + kSamplePeriod;
  samples_.push_back(sample);
}

void ReportOutputs::OnFlightEnd(const Simulation& sim, const FlightResult& result) {
  flown_ = true;
  result_ = result;
  end_position_ = sim.VehicleState().p_W;
}

void ReportOutputs::OnDiscovery(const std::vector<double>& revealed_at,
                                const std::vector<ReplanEvent>& replans) {
  revealed_at_ = revealed_at;
  if (replans.size() != replans_.size()) replans_ = replans;
}

std::string ReportOutputs::Write(const std::string& summary_json, const std::string& command,
                                 const ReportScripts& scripts) const {
  std::ostringstream out;
  Numbers n(out);
  const Map& map = setup_.map;
  std::string summary = summary_json;  // never "</script>" inside the page's data
  for (size_t at = summary.find("</"); at != std::string::npos; at = summary.find("</", at + 3)) {
    summary.replace(at, 2, "<\\/");
  }
  out << "{\"name\":" << JsonQuoted(setup_.name) << ",\"command\":" << JsonQuoted(command)
      << ",\"summary\":" << summary << ",\"plan\":" << plan_json_ << ",\"bounds\":[";
  n.Point(map.bounds.min);
  out << ",";
  n.Point(map.bounds.max);
  out << "],\"boxes\":[";
  for (size_t i = 0; i < map.boxes.size(); ++i) {
    const Box& box = map.boxes[i];
    if (i) out << ",";
    out << "{\"name\":" << JsonQuoted(box.name) << ",\"min\":";
    n.Point(box.extent.min);
    out << ",\"max\":";
    n.Point(box.extent.max);
    out << ",\"rgb\":";
    n.Point(box.rgb, 3);
    const bool unknown = i < setup_.unknown.size() && setup_.unknown[i];
    if (unknown) {
      // when the sensor revealed it [s] (-1: never)
      out << ",\"revealed\":";
      n.Number(i < revealed_at_.size() ? revealed_at_[i] : -1.0, 3);
    }
    out << "}";
  }
  out << "],\"replans\":[";
  for (size_t i = 0; i < replans_.size(); ++i) {
    if (i) out << ",";
    out << "{\"t\":";
    n.Number(replans_[i].t, 3);
    out << ",\"trigger\":" << JsonQuoted(replans_[i].trigger)
        << ",\"outcome\":" << JsonQuoted(replans_[i].outcome) << ",\"abandoned\":";
    n.Points(replans_[i].abandoned, 3);
    out << ",\"replacement\":";
    n.Points(replans_[i].replacement, 3);
    out << ",\"speeds\":[";
    for (size_t k = 0; k < replans_[i].replacement_speeds.size(); ++k) {
      if (k) out << ",";
      n.Number(replans_[i].replacement_speeds[k], 3);
    }
    out << "]}";
  }
  const QuadParams& v = setup_.vehicle;
  out << "],\"vehicle\":{\"size\":";
  n.Point(v.collision_size);
  out << ",\"max_thrust\":";
  n.Number(v.MaxRotorThrust());
  out << "},\"failure\":";
  if (flown_ && result_.status != FlightStatus::kReachedGoal) {
    out << "{\"status\":" << JsonQuoted(ToString(result_.status))
        << ",\"obstacle\":" << JsonQuoted(result_.obstacle) << ",\"t\":";
    n.Number(result_.time, 3);
    out << ",\"p\":";
    n.Point(end_position_);
    out << "}";
  } else {
    out << "null";
  }
  // the telemetry, one array per column
  const bool windy = setup_.wind.Enabled();
  const auto column = [&](const char* name, int digits, auto value) {
    out << ",\"" << name << "\":[";
    for (size_t i = 0; i < samples_.size(); ++i) {
      if (i) out << ",";
      n.Number(value(samples_[i]), digits);
    }
    out << "]";
  };
  out << ",\"telemetry\":{\"rate\":" << 1.0 / kSamplePeriod;
  column("t", 3, [](const TelemetrySample& s) { return s.t; });
  const char* const axes[] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    column(axes[k], 4, [k](const TelemetrySample& s) { return s.state.p_W[k]; });
  }
  for (int k = 0; k < 3; ++k) {
    const std::string name = std::string(axes[k]) + "_des";
    column(name.c_str(), 4, [k](const TelemetrySample& s) { return s.setpoint.p_W[k]; });
  }
  column("qw", 4, [](const TelemetrySample& s) { return s.state.q_WB.w(); });
  column("qx", 4, [](const TelemetrySample& s) { return s.state.q_WB.x(); });
  column("qy", 4, [](const TelemetrySample& s) { return s.state.q_WB.y(); });
  column("qz", 4, [](const TelemetrySample& s) { return s.state.q_WB.z(); });
  column("speed", 3, [](const TelemetrySample& s) { return s.state.v_W.norm(); });
  column("speed_des", 3, [](const TelemetrySample& s) { return s.setpoint.v_W.norm(); });
  column("error", 4, [](const TelemetrySample& s) { return s.position_error; });
  column("clearance", 4, [](const TelemetrySample& s) { return s.clearance; });
  for (int r = 0; r < 4; ++r) {
    const std::string name = "f" + std::to_string(r + 1);
    column(name.c_str(), 4, [r](const TelemetrySample& s) { return s.rotor_thrusts[r]; });
  }
  if (windy) {
    for (int k = 0; k < 3; ++k) {
      const std::string name = std::string("wind_") + axes[k];
      column(name.c_str(), 3, [k](const TelemetrySample& s) { return s.wind_W[k]; });
    }
  }
  out << "}}";

  // the data last: nothing in it is taken for a marker
  std::string page = ReportPageTemplate();
  Replace(&page, "AEROBOX_TITLE", XmlEscaped(setup_.name));
  Replace(&page, "/*AEROBOX_THREE*/", Script(scripts.three));
  Replace(&page, "/*AEROBOX_ORBIT_CONTROLS*/", Script(scripts.orbit_controls));
  Replace(&page, "/*AEROBOX_CHART*/", Script(scripts.chart));
  Replace(&page, "/*AEROBOX_DATA*/", out.str());
  const std::string path = (fs::path(folder_) / "report.html").string();
  WriteFileAtomically(path, page);
  return path;
}

}  // namespace aerobox
