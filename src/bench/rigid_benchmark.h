// aerobox bench --sections rl, the rigid backend: its environment steps per second against
// MuJoCo's in the same run, at MuJoCo's 1 ms step and at the peers' integration steps, and where
// its time goes.
#pragma once

#include <ostream>

#include "bench/benchmark_medians.h"

namespace aerobox {

void RunRigidBenchmark(std::ostream& out, const BenchSize& size);

}  // namespace aerobox
