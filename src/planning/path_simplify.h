// Polylines: their length, a head and the point nearest another; shortening a collision-free
// polyline while keeping it collision-free.
#pragma once

#include <random>
#include <vector>

#include "common/types.h"
#include "planning/validity.h"

namespace aerobox {

// Total length of a polyline [m].
double PathLength(const std::vector<Vec3>& path);

// The polyline `path` up to `arc` [m] along it: its vertices before, then the point there (the
// whole path when `arc` passes its end).
std::vector<Vec3> PathHead(const std::vector<Vec3>& path, double arc);

// [m] along the polyline `path` to its point nearest `p`.
double ArcNearest(const std::vector<Vec3>& path, const Vec3& p);

// Random shortcuts (as OMPL's PathSimplifier::shortcutPath does): pick two points anywhere on
// the path, and when the straight motion between them is valid, replace what lies between.
// `attempts` tries; the ends never move. The result is never longer.
void ShortcutPath(const Validity& validity, int attempts, std::mt19937_64* rng,
                  std::vector<Vec3>* path);

// Drops every waypoint whose neighbours see each other (greedy, from the start).
void PruneWaypoints(const Validity& validity, std::vector<Vec3>* path);

}  // namespace aerobox
