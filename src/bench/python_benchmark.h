// aerobox bench --sections python: runs src/bench/python_control.py with Debian's python3 and the
// build's aerobox package, and copies its table to `out`.
#pragma once

#include <ostream>
#include <string>

namespace aerobox {

// Throws std::runtime_error when python3 cannot be started or the script fails.
void RunPythonBenchmark(const std::string& window_scenario, std::ostream& out);

}  // namespace aerobox
