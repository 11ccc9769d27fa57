// OctoMap 1.9 (Debian's liboctomap-dev), the occupancy map our users know from Fast-Planner and
// ROS, as the reference of our voxel grid (perception/occupancy_grid.h): the same depth frames
// fused into its octree, for the navigation benchmark's comparison of cost, memory and quality.
// Its types stay in the .cpp.
#pragma once

#include <memory>
#include <vector>

#include "common/types.h"
#include "perception/depth_camera.h"
#include "perception/occupancy_grid.h"

namespace aerobox {

class OctoMapReference {
 public:
  explicit OctoMapReference(double resolution);  // [m]
  ~OctoMapReference();
  OctoMapReference(const OctoMapReference&) = delete;
  OctoMapReference& operator=(const OctoMapReference&) = delete;

  // One frame as a point cloud, with OctoMap's insertPointCloud at `range` [m] and its
  // `discretize` (one ray per end cell, as our grid walks): every returning pixel's point (the
  // floor's too: OctoMap knows no floor), and for a pixel that saw nothing a point just beyond
  // the range, which OctoMap then only clears up to the range. Dropped pixels say nothing.
  void Insert(const DepthImage& image, double range);

  Occupancy At(const Vec3& p) const;
  // The centres of the occupied cells inside `bounds`, at the resolution (a pruned leaf counts
  // as every cell it holds) [m].
  std::vector<Vec3> OccupiedCentres(const Aabb& bounds) const;
  long memory() const;  // [bytes] the octree's own estimate

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace aerobox
