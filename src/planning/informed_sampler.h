// Uniform samples from the part of a box that can still improve a path (Gammell, Srinivasa and
// Barfoot 2014, "Informed RRT*"): the prolate spheroid of points x with
// |x - start| + |x - goal| <= best cost.
#pragma once

#include <random>

#include "common/types.h"

namespace aerobox {

class InformedSampler {
 public:
  InformedSampler(const Vec3& start, const Vec3& goal, const Aabb& bounds);

  // A uniform sample of `bounds` (no solution yet: best_cost is +infinity) or of the spheroid
  // intersected with `bounds`. Never fails: after many rejections it returns a sample of the
  // spheroid's part clamped into `bounds`.
  Vec3 Sample(double best_cost, std::mt19937_64* rng) const;

 private:
  Vec3 SampleBounds(std::mt19937_64* rng) const;
  Vec3 SampleSpheroid(double best_cost, std::mt19937_64* rng) const;

  Vec3 centre_;
  Mat3 rotation_;    // world <- spheroid frame (x along start -> goal)
  double min_cost_;  // |goal - start| [m]
  Aabb bounds_;
};

}  // namespace aerobox
