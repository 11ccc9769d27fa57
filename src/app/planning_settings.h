// What a scenario's [planner] table sets: the collision margin and RRT*'s parameters.
#pragma once

#include "geometry/collision_world.h"
#include "planning/rrt_star.h"

namespace aerobox {

// The app's planner defaults differ from RrtStarParams' in one way: they stop on an iteration
// count, so that the same seed gives the same path on any machine; the time budget is only a
// safety cap.
struct PlanningSettings {
  CollisionParams collision;
  RrtStarParams rrt = [] {
    RrtStarParams p;
    p.max_iterations = 4000;
    p.time_budget = 10.0;
    return p;
  }();
};

}  // namespace aerobox
