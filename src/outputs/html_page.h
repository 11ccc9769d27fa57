// The pages aerobox writes (a run's report.html, a sweep's report.html) are made one way: a page
// kept as an .html file beside its code and built into the library by CMake
// (aerobox_embed_page), with markers where the title, Debian's packaged scripts and the data go.
// The data is JSON (written by nlohmann-json in the page's .cpp), placed last so that nothing in
// it is taken for a marker.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace aerobox {

// Where the pages' scripts come from: Debian's libjs-three and libjs-chart.js.
struct ReportScripts {
  std::string three = "/usr/share/javascript/three/three.min.js";
  std::string orbit_controls = "/usr/share/javascript/three/examples/js/controls/OrbitControls.js";
  std::string chart = "/usr/share/javascript/chart.js/chart.min.js";
};

// The text of a page's script; throws InputError naming `path` when it is missing or empty
// (install libjs-three and libjs-chart.js with tools/setup.sh, or leave the page out).
std::string ReadPageScript(const std::string& path);

struct PageParts {
  std::string title;                                         // shown escaped
  std::vector<std::pair<std::string, std::string>> scripts;  // marker, the script's text
  std::string data_json;                                     // "</" is escaped in the page
};

// `page` with the markers AEROBOX_TITLE, each script's marker and /*AEROBOX_DATA*/ replaced.
// Throws std::logic_error when the page lacks a marker (a page and its code disagree).
std::string FillPage(std::string page, const PageParts& parts);

}  // namespace aerobox
