// Minimum-snap solve times: Ipopt (equalities only, and with corridors) against the closed-form
// KKT solve, on the same problems, in one run (Google Benchmark, medians of repetitions).
#pragma once

#include <ostream>

#include "bench/benchmark_medians.h"
#include "common/progress.h"

namespace aerobox {

// Prints a markdown table for 5 to 200 segments (5 and 10 in a smoke run); progress goes to
// `progress`.
void CompareMinSnapSolvers(std::ostream& out, ProgressDisplay& progress, const BenchSize& size);

}  // namespace aerobox
