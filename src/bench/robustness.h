// Flights that push back: every map over seeds and mean winds, with Dryden turbulence, drag,
// an IMU and motion capture, the controller flying on the estimate.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "common/progress.h"

namespace aerobox {

struct RobustnessParams {
  std::vector<std::string> scenarios;           // scenario.toml files
  std::vector<double> winds = {0.0, 2.0, 4.0};  // mean wind speeds [m/s]
  int seeds = 20;                               // seeds 1..seeds per map and wind
  std::string csv;                              // one row per flight there ("": none)
};

// Prints the Markdown table (per map and wind: success rate, tracking RMS median and worst,
// minimum clearance, estimate RMS median, the failures by seed); progress goes to `progress`.
void RobustnessTable(const RobustnessParams& params, std::ostream& out, ProgressDisplay& progress);

}  // namespace aerobox
