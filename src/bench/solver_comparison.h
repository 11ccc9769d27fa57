// Minimum-snap solve times: Ipopt (equalities only, and with corridors) against the closed-form
// KKT solve, on the same problems, in one run (Google Benchmark, medians of repetitions).
#pragma once

#include <ostream>

namespace aerobox {

// Prints a markdown table for 5, 10, 20 and 50 segments; progress goes to `progress`.
void CompareMinSnapSolvers(std::ostream& out, std::ostream& progress);

}  // namespace aerobox
