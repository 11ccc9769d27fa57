// An obstacle map: bounds, axis-aligned boxes with colours, optional start and goal.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/types.h"

namespace aerobox {

struct Box {
  Aabb extent;                     // world frame [m]
  Vec3 rgb = Vec3(0.6, 0.6, 0.6);  // colour, each component in [0, 1]
  std::string name;                // unique within the map, e.g. "block_3"
  int line = 0;                    // line of the source file it came from (0: unknown)
};

struct Map {
  std::string name;     // e.g. the file's stem: "test_window"
  std::string source;   // file it was read from, for messages
  Aabb bounds;          // the flyable volume [m]
  int bounds_line = 0;  // line of the bounds in the source file (0: unknown)
  std::vector<Box> boxes;
  std::optional<Vec3> start;  // [m], when the file gives one
  std::optional<Vec3> goal;   // [m], when the file gives one
  int start_goal_line = 0;    // line where start/goal were given (0: unknown)
};

// Largest coordinate a map may use [m]: a thousand kilometres. Beyond it, a number is a typo
// or garbage, and the planners' arithmetic would lose all precision.
inline constexpr double kMaxCoordinate = 1e6;

// Checks the invariants the readers promise (finite numbers within kMaxCoordinate, min < max,
// colours in [0, 1], unique names); throws InputError naming the offending box's line.
void ValidateMap(const Map& map);

// Indices of boxes that reach outside the bounds. They are kept (real maps have them, e.g. a
// maze wall at x 10..10.1 in a 10 m map) and reported by `aerobox check`.
std::vector<size_t> BoxesOutsideBounds(const Map& map);

// Index of the first box whose interior overlaps `query`, if any.
std::optional<size_t> FirstOverlappingBox(const Map& map, const Aabb& query);

// Where the vehicle stands when a map gives no start: the first point of a 0.25 m grid over the
// floor, scanned from the (xmin, ymin) corner, where a cube of side `2 * clearance` [m] around the
// vehicle's position touches no box and stays inside the bounds; where blocks cover the floor,
// the same on the tops of the blocks (lowest first). `half_height` [m] lifts the vehicle's
// centre so that it rests on what is below it. Returns nothing when no grid point is free.
std::optional<Vec3> DefaultStart(const Map& map, double clearance, double half_height);

}  // namespace aerobox
