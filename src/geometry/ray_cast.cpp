#include "geometry/ray_cast.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace aerobox {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

double RayToBox(const Vec3& o, const Vec3& d, const Aabb& box) {
  double enter = 0.0, leave = kInf;
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0.0) {
      if (o[i] < box.min[i] || o[i] > box.max[i]) return kInf;  // parallel, outside the slab
      continue;
    }
    double near = (box.min[i] - o[i]) / d[i], far = (box.max[i] - o[i]) / d[i];
    if (near > far) std::swap(near, far);
    enter = std::max(enter, near);
    leave = std::min(leave, far);
    if (enter > leave) return kInf;
  }
  return enter;
}

double RayOutOf(const Vec3& o, const Vec3& d, const Aabb& bounds) {
  double leave = kInf;
  for (int i = 0; i < 3; ++i) {
    if (d[i] > 0.0) leave = std::min(leave, (bounds.max[i] - o[i]) / d[i]);
    if (d[i] < 0.0) leave = std::min(leave, (bounds.min[i] - o[i]) / d[i]);
  }
  return std::max(0.0, leave);
}

double CastRay(const std::vector<Aabb>& boxes, const Aabb& bounds, const Vec3& o, const Vec3& d,
               double range) {
  double nearest = std::min(range, RayOutOf(o, d, bounds));
  for (const Aabb& box : boxes) nearest = std::min(nearest, RayToBox(o, d, box));
  return nearest;
}

}  // namespace aerobox
