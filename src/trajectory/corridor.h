// Safe corridors: an axis-aligned free box around each straight segment, grown face by face
// until it touches an obstacle or the bounds (the free space as the vehicle's centre sees it).
#pragma once

#include <functional>
#include <optional>

#include "common/types.h"

namespace aerobox {

// True when a box of vehicle-centre positions [m] is entirely free.
using BoxFree = std::function<bool(const Aabb&)>;

// The box spanned by a and b, each face pushed out by up to `max_growth` [m] (binary search
// to 1 mm, face after face) while it stays free. Nothing when even the
// segment's own bounding box is not free (a diagonal segment past an obstacle's corner).
std::optional<Aabb> GrowCorridor(const Vec3& a, const Vec3& b, const BoxFree& box_free,
                                 double max_growth);

// The corridor with every face moved inwards by `margin` [m], but never past a or b (the
// segment's ends must stay inside). Used as the constraint box so that the trajectory between
// constrained samples stays inside the corridor itself.
Aabb ShrinkCorridor(const Aabb& corridor, const Vec3& a, const Vec3& b, double margin);

}  // namespace aerobox
