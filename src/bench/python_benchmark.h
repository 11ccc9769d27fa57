// aerobox bench --sections python: runs src/bench/python_control.py with Debian's python3 and the
// build's aerobox package, and copies its table to `out`.
#pragma once

#include <ostream>
#include <string>

#include "bench/benchmark_medians.h"

namespace aerobox {

// Throws std::runtime_error when python3 cannot be started or the script fails.
// A smoke run flies each controller once, at 100 Hz only.
void RunPythonBenchmark(const std::string& window_scenario, std::ostream& out,
                        const BenchSize& size);

}  // namespace aerobox
