// Frames per second of the whole video path (render, read back, encode H.264 on the worker
// thread) against bare render + read back with the same settings, in one run.
#pragma once

#include <ostream>
#include <string>

#include "bench/benchmark_medians.h"
#include "common/progress.h"

namespace aerobox {

// A smoke run renders 4 frames once per case.
void CompareVideoPath(const std::string& scenario, std::ostream& out, ProgressDisplay& progress,
                      const BenchSize& size);

}  // namespace aerobox
