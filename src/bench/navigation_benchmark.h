// Navigation through unknown forests with the depth camera: Fast-Planner's benchmark forest
// (40 x 20 x 5 m, 150 pillars 1.0-1.4 m wide) and EGO-Planner's denser one (200), every pillar
// unknown until the camera sees it; success, contacts, how much faster than real time, where
// the time goes (ray casting, fusion, the planner's world, replanning, the rest), and the
// occupancy map's precision and recall against the true boxes.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "bench/benchmark_medians.h"
#include "common/progress.h"

namespace aerobox {

struct NavigationBenchParams {
  std::string scenario;                  // the depth-camera scenario whose settings fly
  std::vector<int> densities{150, 200};  // pillars per forest
  int seeds = 20;
  double max_speed = 3.0;  // [m/s]
  BenchSize size;
};

void NavigationTable(const NavigationBenchParams& params, std::ostream& out,
                     ProgressDisplay& progress);

}  // namespace aerobox
