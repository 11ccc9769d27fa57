// Closed-loop stepping rate (controller + telemetry + MuJoCo) against bare mj_step on the same
// model, in one run (Google Benchmark, medians of repetitions).
#pragma once

#include <ostream>
#include <string>

#include "bench/benchmark_medians.h"
#include "common/progress.h"

namespace aerobox {

// `scenario`: the scene to step (its trajectory is flown). Prints a markdown table.
// A smoke run flies one window once.
void CompareClosedLoop(const std::string& scenario, std::ostream& out, ProgressDisplay& progress,
                       const BenchSize& size);

}  // namespace aerobox
