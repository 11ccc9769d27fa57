// The report of a sweep: per cell of its grid (a scenario and one value of each grid key, over
// the seeds), the share of runs that reached their goal and the spread of flight time, tracking
// error and clearance; Markdown, CSV and two SVG plots.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace aerobox {

// `manifest`: sweep.json (name, grid keys, runs in order); `results`: by run id. Writes
// report.md, report.csv, success.svg, tracking.svg and report.html (with Chart.js copied in,
// when libjs-chart.js is there) into `folder` and returns their paths, report.md first. Nothing in
// them depends on wall times or hosts: the same results give the same bytes.
std::vector<std::string> WriteSweepReport(const nlohmann::json& manifest,
                                          const std::map<std::string, nlohmann::json>& results,
                                          const std::string& folder);

}  // namespace aerobox
