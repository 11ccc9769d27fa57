// The obstacle map as the vehicle sees it: every box grown by the vehicle's half-size plus a
// clearance, so that "the vehicle's box at p is free" becomes "p lies outside every grown box".
// That makes segment checks exact: the vehicle's axis-aligned box swept along a straight segment
// touches an obstacle exactly when the segment enters the obstacle grown by the vehicle's box.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "common/types.h"
#include "map/map.h"

namespace aerobox {

struct CollisionParams {
  // Full sides of the vehicle's box [m] (QuadParams::collision_size).
  Vec3 vehicle_size = Vec3(0.10, 0.10, 0.05);
  // Extra margin on every side [m], >= 0: room for the controller's tracking error (its flights
  // stay within a few centimetres of the trajectory).
  double clearance = 0.10;

  // Throws std::invalid_argument naming the field when a value is not usable.
  void Validate() const;
  // Vehicle half-size plus clearance [m]: how far every obstacle is grown.
  Vec3 Margin() const { return 0.5 * vehicle_size.array() + clearance; }
};

// A point moved into the free bounds, and by how much.
struct Projection {
  Vec3 point = Vec3::Zero();
  double moved = 0.0;  // [m]
};

class CollisionWorld {
 public:
  CollisionWorld(const Map& map, const CollisionParams& params);
  ~CollisionWorld();
  CollisionWorld(CollisionWorld&&) noexcept;
  CollisionWorld& operator=(CollisionWorld&&) noexcept;

  // Where the vehicle's centre may be: the map bounds shrunk by Margin() on every side (the
  // bounds count as walls, the floor is one). Empty (min > max) when the map is too small.
  const Aabb& free_bounds() const { return free_bounds_; }
  const CollisionParams& params() const { return params_; }

  // True when the vehicle's centre at p lies in free_bounds() and outside every grown obstacle
  // (on a grown obstacle's surface counts as free: the vehicle then keeps exactly `clearance`).
  bool IsPointFree(const Vec3& p) const;

  // True when the vehicle's box, carried along the straight segment a -> b without rotating,
  // keeps `clearance` from every obstacle and stays within the bounds. Exact, not sampled.
  bool IsSegmentFree(const Vec3& a, const Vec3& b) const;

  // True when every vehicle-centre position in `box` [m] is free: the box lies in free_bounds()
  // and meets no grown obstacle's interior. (Safe corridors are built from this.)
  bool IsBoxFree(const Aabb& box) const;

  // Distance from the vehicle's box at p (without clearance) to the nearest map box [m]; 0 when
  // they touch or overlap; +infinity for a map without boxes. The floor and the bounds are
  // not obstacles here.
  double Clearance(const Vec3& p) const;

  // Index of a map box that the vehicle's box at p overlaps (without clearance), if any.
  std::optional<size_t> OverlappingBox(const Vec3& p) const;
  // Index of the map box that makes p not free, for messages: the one whose grown box (by
  // Margin()) contains p or lies within a millimetre of it; nothing when only the bounds do.
  std::optional<size_t> BlockingBox(const Vec3& p) const;

  // All queries are const and may run on several threads at once.

  // The point of free_bounds() nearest to p (p itself when it lies inside).
  Projection ProjectIntoFreeBounds(const Vec3& p) const;

 private:
  class Tree;  // a bounding volume hierarchy over the grown boxes, hidden from the header

  CollisionParams params_;
  Aabb free_bounds_;
  std::vector<Aabb> boxes_;  // the map's boxes
  std::vector<Aabb> grown_;  // the same boxes grown by Margin()
  std::unique_ptr<Tree> tree_;
};

}  // namespace aerobox
