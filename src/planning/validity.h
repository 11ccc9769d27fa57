// How a planner learns what is free: two functions, nothing about maps or collision libraries
// (OMPL's StateValidityChecker and MotionValidator play the same part).
#pragma once

#include <functional>

#include "common/types.h"

namespace aerobox {

struct Validity {
  // True when the vehicle may be at this point [m, world].
  std::function<bool(const Vec3&)> state;
  // True when the whole straight motion between two valid points is free (exactly, for the
  // planner's guarantees to hold: aerobox's CollisionWorld::IsSegmentFree is).
  std::function<bool(const Vec3&, const Vec3&)> motion;
};

}  // namespace aerobox
