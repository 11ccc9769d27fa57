// The page report.html is made from (report_page.html, built into the library), with markers
// where the scripts and the run's data go.
#pragma once

#include <string>

namespace aerobox {

const std::string& ReportPageTemplate();

}  // namespace aerobox
