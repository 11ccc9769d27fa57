// aerobox bench --sections swarm: several vehicles in one world. The cost of N vehicles, each
// with its own controller at 500 Hz, against one vehicle alone in the same run; and the
// antipodal swap of 4, 8 and 16 Crazyflies through prioritised planning, with the makespan
// against each vehicle flying alone.
#pragma once

#include <ostream>
#include <string>

#include "bench/benchmark_medians.h"

namespace aerobox {

// `swap_scenario`: scenes/swarm_swap/scenario.toml (its room and settings; the vehicles are
// placed by the benchmark).
void RunSwarmBenchmark(const std::string& swap_scenario, std::ostream& out, const BenchSize& size);

}  // namespace aerobox
