// Rays against axis-aligned boxes, exact (the slab method): what a range sensor sees of a map
// whose obstacles are boxes. Used by the learning environments' range observation; pure math.
#pragma once

#include <vector>

#include "common/types.h"

namespace aerobox {

// The distance [m] along the unit direction `d` from `o` at which the ray enters `box`, or
// +infinity when it never does. A ray starting inside the box hits it at 0.
double RayToBox(const Vec3& o, const Vec3& d, const Aabb& box);

// The distance [m] along the unit direction `d` from `o` (inside `bounds`) at which the ray
// leaves `bounds`.
double RayOutOf(const Vec3& o, const Vec3& d, const Aabb& bounds);

// The nearest of the ray's hits on `boxes` and its exit from `bounds`, at most `range` [m].
double CastRay(const std::vector<Aabb>& boxes, const Aabb& bounds, const Vec3& o, const Vec3& d,
               double range);

}  // namespace aerobox
