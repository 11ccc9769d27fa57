// Flights with obstacles discovered on the way: every map with a share of its boxes unknown to
// the planner, over seeds; success, contacts, replans and their latency (trigger to the new
// trajectory ready, wall time).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "common/progress.h"

namespace aerobox {

void ReplanningTable(const std::vector<std::string>& scenarios, int seeds, double fraction,
                     std::ostream& out, ProgressDisplay& progress);

}  // namespace aerobox
