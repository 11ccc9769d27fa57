// A random forest after Fast-Planner's benchmark (its random_forest: pillars of random width
// over a W x L area, full height, optional horizontal bars), seeded, as an aerobox map with the
// start and goal at the two ends, clear of every pillar.
#pragma once

#include <cstdint>
#include <string>

#include "common/schema.h"
#include "map/map.h"

namespace aerobox {

struct ForestParams {
  Vec3 size = Vec3(40, 20, 5);  // [m] W (along x, start to goal) x L x H
  int pillars = 150;            // Fast-Planner's density; EGO-Planner's denser variant: 200
  double width_min = 1.0;       // [m] a pillar's side
  double width_max = 1.4;       // [m]
  int bars = 0;                 // horizontal bars between the pillars
  double clear_ends = 3.0;      // [m] of each end along x left free for the start and the goal
  long seed = 1;

  void Describe(Archive& a);  // (common/schema.h)
  void Validate() const;      // throws std::invalid_argument naming the field
};

// The forest: the pillars, then the bars, named block_N in that order (as a map file read back
// names them), start (1, L/2, 1) and goal (W - 1, L/2, 1).
Map MakeForest(const ForestParams& params);

// A map as flightsim's JSON (bounds, blocks with extents and colours, start, goal), which the
// JSON reader reads back to the same boxes exactly.
std::string MapJson(const Map& map);

}  // namespace aerobox
