// Shortening a collision-free polyline while keeping it collision-free.
#pragma once

#include <random>
#include <vector>

#include "common/types.h"
#include "planning/validity.h"

namespace aerobox {

// Total length of a polyline [m].
double PathLength(const std::vector<Vec3>& path);

// Random shortcuts (as OMPL's PathSimplifier::shortcutPath does): pick two points anywhere on
// the path, and when the straight motion between them is valid, replace what lies between.
// `attempts` tries; the ends never move. The result is never longer.
void ShortcutPath(const Validity& validity, int attempts, std::mt19937_64* rng,
                  std::vector<Vec3>* path);

// Drops every waypoint whose neighbours see each other (greedy, from the start).
void PruneWaypoints(const Validity& validity, std::vector<Vec3>* path);

}  // namespace aerobox
