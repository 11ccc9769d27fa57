// City scale (the FCND San Francisco map): the lattice built once and queried with seeded random
// start and goal pairs 600-700 m apart, the trajectory along the longest path found, and
// MuJoCo's steps per second in the city against the window scene, all in one run.
#pragma once

#include <ostream>
#include <string>

#include "bench/benchmark_medians.h"
#include "common/progress.h"

namespace aerobox {

// `city`: the map file; `window`: the window scenario. Prints markdown tables.
// A smoke run times MuJoCo once per scene.
void CityBenchmark(const std::string& city, const std::string& window, int queries,
                   std::ostream& out, ProgressDisplay& progress, const BenchSize& size);

}  // namespace aerobox
