// aerobox bench --sections rl: the learning environments' steps per second, one world and N in
// threads, against the bare physics of the same worlds in the same run.
#pragma once

#include <ostream>

#include "bench/benchmark_medians.h"

namespace aerobox {

void RunRlBenchmark(std::ostream& out, const BenchSize& size);

}  // namespace aerobox
