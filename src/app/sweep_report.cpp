#include "app/sweep_report.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "common/error.h"
#include "common/quoting.h"
#include "outputs/files.h"
#include "outputs/html_page.h"

namespace aerobox {
namespace fs = std::filesystem;
using Json = nlohmann::json;

// sweep_page.html, built in by CMake (aerobox_embed_page): the cells as a table and two charts
const std::string& SweepPageTemplate();

namespace {

struct Cell {
  std::string scenario;
  Json params;
  int runs = 0;     // in the sweep
  int results = 0;  // with a result
  int reached = 0;
  std::map<std::string, int> failures;  // by status (and the box hit)
  std::vector<double> flight_time;      // [s], runs that reached the goal
  std::vector<double> tracking_rms;     // [m], runs that flew
  std::vector<double> clearance;        // [m], runs that flew among obstacles
};

// Nearest rank: the smallest value with at least q of the values at or below it.
double Percentile(std::vector<double> values, double q) {
  if (values.empty()) return NAN;
  std::sort(values.begin(), values.end());
  const size_t rank = static_cast<size_t>(std::ceil(q * static_cast<double>(values.size())));
  return values[std::min(values.size() - 1, rank == 0 ? 0 : rank - 1)];
}

std::string Number(double value, int digits) {
  if (!std::isfinite(value)) return "";
  std::ostringstream text;
  text << std::fixed << std::setprecision(digits) << value;
  return text.str();
}

std::string ParamText(const Json& value) {
  return value.is_string() ? value.get<std::string>() : value.dump();
}

std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string CellLabel(const Cell& cell) {
  std::string label = cell.scenario;
  for (const auto& [key, value] : cell.params.items()) label += ", " + key + "=" + ParamText(value);
  return label;
}

// A horizontal bar per cell: the value, and a thin whisker to `high` when given.
std::string BarChart(const std::string& title, const std::string& unit,
                     const std::vector<std::string>& labels, const std::vector<double>& values,
                     const std::vector<double>& high, double top) {
  constexpr int kLabel = 340, kBar = 360, kRow = 22, kHead = 40;
  const int width = kLabel + kBar + 90;
  const int height = kHead + kRow * static_cast<int>(labels.size()) + 30;
  if (!(top > 0)) top = 1;
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"10\" y=\"22\" font-size=\"15\">" << XmlEscaped(title) << "</text>\n";
  for (size_t i = 0; i < labels.size(); ++i) {
    const int y = kHead + kRow * static_cast<int>(i);
    svg << "<text x=\"" << kLabel - 8 << "\" y=\"" << y + 15 << "\" text-anchor=\"end\">"
        << XmlEscaped(labels[i]) << "</text>\n";
    if (!std::isfinite(values[i])) {
      svg << "<text x=\"" << kLabel + 4 << "\" y=\"" << y + 15 << "\">no value</text>\n";
      continue;
    }
    const double w = kBar * std::clamp(values[i] / top, 0.0, 1.0);
    svg << "<rect x=\"" << kLabel << "\" y=\"" << y + 3 << "\" width=\"" << Number(w, 1)
        << "\" height=\"" << kRow - 6 << "\" fill=\"#3b75af\"/>\n";
    double end = w;
    if (!high.empty() && std::isfinite(high[i])) {
      end = kBar * std::clamp(high[i] / top, 0.0, 1.0);
      svg << "<line x1=\"" << Number(kLabel + w, 1) << "\" x2=\"" << Number(kLabel + end, 1)
          << "\" y1=\"" << y + kRow / 2 << "\" y2=\"" << y + kRow / 2
          << "\" stroke=\"#222\" stroke-width=\"1.5\"/>\n";
    }
    svg << "<text x=\"" << Number(kLabel + std::max(w, end) + 6, 1) << "\" y=\"" << y + 15 << "\">"
        << Number(values[i], unit == "%" ? 0 : 4) << " " << XmlEscaped(unit) << "</text>\n";
  }
  const int axis = kHead + kRow * static_cast<int>(labels.size()) + 4;
  svg << "<line x1=\"" << kLabel << "\" x2=\"" << kLabel + kBar << "\" y1=\"" << axis << "\" y2=\""
      << axis << "\" stroke=\"#888\"/>\n"
      << "<text x=\"" << kLabel << "\" y=\"" << axis + 16 << "\">0</text>\n"
      << "<text x=\"" << kLabel + kBar << "\" y=\"" << axis + 16 << "\" text-anchor=\"end\">"
      << Number(top, unit == "%" ? 0 : 2) << " " << XmlEscaped(unit) << "</text>\n</svg>\n";
  return svg.str();
}

}  // namespace

std::vector<std::string> WriteSweepReport(const Json& manifest,
                                          const std::map<std::string, Json>& results,
                                          const std::string& folder) {
  std::vector<std::string> keys;
  for (const Json& key : manifest.value("grid", Json::array())) keys.push_back(key);
  // the cells in the sweep's order
  std::vector<Cell> cells;
  std::map<std::string, size_t> index;
  for (const Json& run : manifest["runs"]) {
    const std::string scenario = run["scenario"].get<std::string>();
    const std::string key = scenario + "\n" + run["params"].dump();
    auto [it, added] = index.emplace(key, cells.size());
    if (added) {
      cells.emplace_back();
      cells.back().scenario = scenario;
      cells.back().params = run["params"];
    }
    Cell& cell = cells[it->second];
    ++cell.runs;
    const auto found = results.find(run["id"].get<std::string>());
    if (found == results.end()) continue;
    const Json& result = found->second;
    ++cell.results;
    const std::string status = result.value("status", "");
    const Json summary = result.value("summary", Json::object());
    if (status == "reached goal") {
      ++cell.reached;
      if (summary.contains("flight_time_s")) cell.flight_time.push_back(summary["flight_time_s"]);
    } else {
      std::string why = summary.value("flight_status", status);
      if (summary.contains("collision_with") && summary["collision_with"].is_string()) {
        why += " (" + summary["collision_with"].get<std::string>() + ")";
      }
      ++cell.failures[why];
    }
    if (summary.contains("tracking_rms_m") && summary["tracking_rms_m"].is_number()) {
      cell.tracking_rms.push_back(summary["tracking_rms_m"]);
    }
    if (summary.contains("min_clearance_m") && summary["min_clearance_m"].is_number()) {
      cell.clearance.push_back(summary["min_clearance_m"]);
    }
  }

  const std::string name = manifest.value("name", "sweep");
  int total = 0, with_result = 0, reached = 0;
  for (const Cell& cell : cells) {
    total += cell.runs;
    with_result += cell.results;
    reached += cell.reached;
  }
  std::ostringstream md, csv;
  md << "# Sweep " << name << "\n\n"
     << total << " runs in " << cells.size() << " cells; " << with_result << " have a result, "
     << reached << " reached their goal.\n\n"
     << "Per cell (a scenario and one value of each grid key, over the seeds): flight time over "
        "the runs that reached the goal, tracking RMS over the runs that flew; each as the median "
        "and the 90th percentile, and the minimum clearance also as the 10th percentile (90 % of "
        "the runs kept at least that much).\n\n"
     << "| scenario |";
  csv << "scenario";
  for (const std::string& key : keys) {
    md << " " << key << " |";
    csv << "," << CsvField(key);
  }
  md << " runs | reached | flight time median / p90 [s] | tracking RMS median / p90 [m] | min "
        "clearance median / p90 / p10 [m] | failures |\n|---|";
  for (size_t i = 0; i < keys.size(); ++i) md << "---|";
  md << "---|---|---|---|---|---|\n";
  csv << ",runs,results,reached,success_rate,flight_time_median_s,flight_time_p90_s,"
         "tracking_rms_median_m,tracking_rms_p90_m,min_clearance_median_m,min_clearance_p90_m,"
         "min_clearance_p10_m\n";
  std::vector<std::string> labels;
  std::vector<double> success, rms_median, rms_p90;
  Json page_cells = Json::array();  // report.html's data
  for (const Cell& cell : cells) {
    const double rate = cell.results > 0 ? 100.0 * cell.reached / cell.results : NAN;
    md << "| " << cell.scenario << " |";
    csv << CsvField(cell.scenario);
    for (const std::string& key : keys) {
      const std::string value = cell.params.contains(key) ? ParamText(cell.params[key]) : "";
      md << " " << value << " |";
      csv << "," << CsvField(value);
    }
    std::string failures;
    for (const auto& [why, count] : cell.failures) {
      failures += (failures.empty() ? "" : ", ") + why + " x" + std::to_string(count);
    }
    if (cell.results < cell.runs) {
      failures += (failures.empty() ? "" : ", ") + std::to_string(cell.runs - cell.results) +
                  " without a result";
    }
    const auto pair = [](const std::vector<double>& v, double q, int digits) {
      if (v.empty()) return std::string("-");
      return Number(Percentile(v, 0.5), digits) + " / " + Number(Percentile(v, q), digits);
    };
    md << " " << cell.runs << " | " << cell.reached << "/" << cell.results << " ("
       << Number(rate, 0) << " %) | " << pair(cell.flight_time, 0.9, 2) << " | "
       << pair(cell.tracking_rms, 0.9, 4) << " | " << pair(cell.clearance, 0.9, 3)
       << (cell.clearance.empty() ? "" : " / " + Number(Percentile(cell.clearance, 0.1), 3))
       << " | " << (failures.empty() ? "none" : failures) << " |\n";
    csv << "," << cell.runs << "," << cell.results << "," << cell.reached << ","
        << Number(rate / 100, 4) << "," << Number(Percentile(cell.flight_time, 0.5), 4) << ","
        << Number(Percentile(cell.flight_time, 0.9), 4) << ","
        << Number(Percentile(cell.tracking_rms, 0.5), 6) << ","
        << Number(Percentile(cell.tracking_rms, 0.9), 6) << ","
        << Number(Percentile(cell.clearance, 0.5), 6) << ","
        << Number(Percentile(cell.clearance, 0.9), 6) << ","
        << Number(Percentile(cell.clearance, 0.1), 6) << "\n";
    const auto value = [](double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); };
    page_cells.push_back(
        {{"scenario", cell.scenario},
         {"params", cell.params},
         {"runs", cell.runs},
         {"results", cell.results},
         {"reached", cell.reached},
         {"flight_time",
          {value(Percentile(cell.flight_time, 0.5)), value(Percentile(cell.flight_time, 0.9))}},
         {"tracking_rms",
          {value(Percentile(cell.tracking_rms, 0.5)), value(Percentile(cell.tracking_rms, 0.9))}},
         {"clearance",
          {value(Percentile(cell.clearance, 0.5)), value(Percentile(cell.clearance, 0.9)),
           value(Percentile(cell.clearance, 0.1))}},
         {"failures", failures}});
    labels.push_back(CellLabel(cell));
    success.push_back(rate);
    rms_median.push_back(Percentile(cell.tracking_rms, 0.5));
    rms_p90.push_back(Percentile(cell.tracking_rms, 0.9));
  }
  md << "\n![runs that reached their goal](success.svg)\n\n"
     << "![tracking RMS, median and 90th percentile](tracking.svg)\n";
  double top_rms = 0;
  for (const double v : rms_p90) {
    if (std::isfinite(v)) top_rms = std::max(top_rms, v);
  }
  const fs::path out(folder);
  std::vector<std::string> paths = {(out / "report.md").string(), (out / "report.csv").string(),
                                    (out / "success.svg").string(),
                                    (out / "tracking.svg").string()};
  WriteFileAtomically(paths[0], md.str());
  WriteFileAtomically(paths[1], csv.str());
  WriteFileAtomically(
      paths[2], BarChart("Runs that reached their goal, per cell", "%", labels, success, {}, 100));
  WriteFileAtomically(paths[3],
                      BarChart("Tracking RMS per cell: median, whisker to the 90th percentile", "m",
                               labels, rms_median, rms_p90, top_rms * 1.1));
  // report.html: the table and the charts in a browser, Chart.js copied in
  const Json data = {{"name", name},       {"runs", total}, {"results", with_result},
                     {"reached", reached}, {"keys", keys},  {"cells", page_cells}};
  PageParts parts;
  parts.title = name;
  try {
    parts.scripts = {{"/*AEROBOX_CHART*/", ReadPageScript(ReportScripts().chart)}};
  } catch (const InputError&) {
    return paths;  // without Debian's Chart.js: report.md, report.csv and the charts, no page
  }
  parts.data_json = data.dump();
  paths.push_back((out / "report.html").string());
  WriteFileAtomically(paths.back(), FillPage(SweepPageTemplate(), parts));
  return paths;
}

}  // namespace aerobox
