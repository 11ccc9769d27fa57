#include "trajectory/corridor.h"

#include <algorithm>

namespace aerobox {

std::optional<Aabb> GrowCorridor(const Vec3& a, const Vec3& b, const BoxFree& box_free,
                                 double max_growth) {
  Aabb box{a.cwiseMin(b), a.cwiseMax(b)};
  if (!box_free(box)) return std::nullopt;
  constexpr double kResolution = 1e-3;  // [m]
  // one pass over the faces: a face that stopped at an obstacle cannot move later, since the
  // other faces only make the box larger
  for (int face = 0; face < 6; ++face) {
    const int axis = face / 2;
    const double sign = face % 2 == 0 ? -1.0 : 1.0;
    const auto extended = [&](double e) {
      Aabb grown = box;
      (sign < 0 ? grown.min : grown.max)[axis] += sign * e;
      return grown;
    };
    // largest free extension in [0, max_growth], by bisection
    double free = 0.0;
    double blocked = max_growth;
    if (box_free(extended(blocked))) {
      free = blocked;
    } else {
      while (blocked - free > kResolution) {
        const double mid = 0.5 * (free + blocked);
        (box_free(extended(mid)) ? free : blocked) = mid;
      }
    }
    box = extended(free);
  }
  return box;
}

Aabb ShrinkCorridor(const Aabb& corridor, const Vec3& a, const Vec3& b, double margin) {
  const Vec3 low = a.cwiseMin(b);
  const Vec3 high = a.cwiseMax(b);
  Aabb shrunk;
  for (int k = 0; k < 3; ++k) {
    shrunk.min[k] = std::min(corridor.min[k] + margin, low[k]);
    shrunk.max[k] = std::max(corridor.max[k] - margin, high[k]);
  }
  return shrunk;
}

}  // namespace aerobox
