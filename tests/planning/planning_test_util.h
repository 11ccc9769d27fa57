// A collision world wrapped as a planner's Validity, and a dense second-method re-check.
#pragma once

#include "geometry/collision_world.h"
#include "planning/validity.h"

namespace aerobox::testing {

inline Validity ValidityOf(const CollisionWorld& world) {
  return {[&world](const Vec3& p) { return world.IsPointFree(p); },
          [&world](const Vec3& a, const Vec3& b) { return world.IsSegmentFree(a, b); }};
}

// Samples the vehicle's box every `spacing` metres along the path and checks, brute force over
// the map's boxes, that it keeps the clearance (touching the grown box is allowed) and stays in
// the bounds. Independent of CollisionWorld's exact segment test.
inline bool DenselyFree(const Map& map, const CollisionParams& params,
                        const std::vector<Vec3>& path, double spacing = 0.01) {
  const Vec3 margin = params.Margin();
  for (size_t i = 1; i < path.size(); ++i) {
    const Vec3 a = path[i - 1];
    const Vec3 b = path[i];
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / spacing)));
    for (int s = 0; s <= n; ++s) {
      const Vec3 p = a + (b - a) * (static_cast<double>(s) / n);
      const Aabb vehicle{p - margin, p + margin};
      if (!vehicle.Inflated(-1e-9).IsInside(map.bounds)) return false;
      for (const Box& box : map.boxes) {
        if (box.extent.Overlaps(vehicle.Inflated(-1e-9))) return false;
      }
    }
  }
  return true;
}

}  // namespace aerobox::testing
