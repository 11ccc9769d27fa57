// The throughput of `aerobox sweep`: one 100-run sweep (the window, 20 seeds x 5 speed limits,
// no video) with one process and with two at a time, in the same command.
#pragma once

#include <ostream>
#include <string>

#include "common/progress.h"

namespace aerobox {

void SweepBenchmark(const std::string& window_scenario, int seeds, std::ostream& out,
                    ProgressDisplay& progress);

}  // namespace aerobox
