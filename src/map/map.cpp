#include "map/map.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "common/error.h"
#include "common/number_format.h"

namespace aerobox {
namespace {

void CheckExtent(const Aabb& box, const SourceLocation& where, const std::string& field) {
  static const char* const kAxes[] = {"x", "y", "z"};
  if (!box.min.allFinite() || !box.max.allFinite()) {
    throw InputError(where, field, "extents must be finite numbers");
  }
  if (box.min.cwiseAbs().maxCoeff() > kMaxCoordinate ||
      box.max.cwiseAbs().maxCoeff() > kMaxCoordinate) {
    throw InputError(where, field,
                     "coordinates must lie within +-" + FormatNumber(kMaxCoordinate) + " m");
  }
  for (int axis = 0; axis < 3; ++axis) {
    if (!(box.min[axis] < box.max[axis])) {
      throw InputError(where, field,
                       std::string(kAxes[axis]) + "min " + FormatNumber(box.min[axis]) +
                           " must be less than " + kAxes[axis] + "max " +
                           FormatNumber(box.max[axis]));
    }
  }
}

}  // namespace

void ValidateMap(const Map& map) {
  // the boxes first: a map whose bounds are derived from its boxes (CSV) is reported at the box
  // that made them bad
  std::set<std::string> names;
  for (const Box& box : map.boxes) {
    const SourceLocation where{map.source, box.line};
    CheckExtent(box.extent, where, box.name);
    if (!((box.rgb.array() >= 0.0).all() && (box.rgb.array() <= 1.0).all())) {
      throw InputError(where, box.name, "colour components must lie in [0, 1]");
    }
    if (!names.insert(box.name).second) {
      throw InputError(where, box.name, "box name is used twice");
    }
  }
  CheckExtent(map.bounds, {map.source, map.bounds_line}, "boundary");
  for (const auto& [point, field] : {std::pair{map.start, "start"}, std::pair{map.goal, "goal"}}) {
    if (point && !point->allFinite()) {
      throw InputError({map.source, map.start_goal_line}, field, "must be three finite numbers");
    }
    if (point && point->cwiseAbs().maxCoeff() > kMaxCoordinate) {
      throw InputError({map.source, map.start_goal_line}, field,
                       "coordinates must lie within +-" + FormatNumber(kMaxCoordinate) + " m");
    }
  }
}

std::vector<size_t> BoxesOutsideBounds(const Map& map) {
  std::vector<size_t> outside;
  for (size_t i = 0; i < map.boxes.size(); ++i) {
    if (!map.boxes[i].extent.IsInside(map.bounds)) outside.push_back(i);
  }
  return outside;
}

std::optional<size_t> FirstOverlappingBox(const Map& map, const Aabb& query) {
  for (size_t i = 0; i < map.boxes.size(); ++i) {
    if (map.boxes[i].extent.Overlaps(query)) return i;
  }
  return std::nullopt;
}

std::optional<Vec3> DefaultStart(const Map& map, double clearance, double half_height) {
  constexpr double kGridStep = 0.25;  // [m] fine enough for the narrowest published map gaps
  const Vec3 size = map.bounds.Size();
  const int nx = static_cast<int>(std::floor(size.x() / kGridStep));
  const int ny = static_cast<int>(std::floor(size.y() / kGridStep));
  // a spot resting on the surface at height `ground`: the cube around the vehicle, cut at the
  // surface, inside the bounds and clear of every box
  const auto free_on = [&](double x, double y, double ground) -> std::optional<Vec3> {
    const Vec3 p(x, y, ground + half_height);
    const Aabb around{p.array() - clearance, p.array() + clearance};
    const Aabb above{Vec3(around.min.x(), around.min.y(), ground), around.max};
    if (!above.IsInside(map.bounds) || FirstOverlappingBox(map, above)) return std::nullopt;
    return p;
  };
  // the floor first, scanned from the (xmin, ymin) corner; then, where blocks cover the floor
  // (some course maps model floor and ceiling as slabs), the tops of the blocks, lowest first
  for (const bool on_blocks : {false, true}) {
    for (int j = 1; j < ny; ++j) {
      for (int i = 1; i < nx; ++i) {
        const double x = map.bounds.min.x() + i * kGridStep;
        const double y = map.bounds.min.y() + j * kGridStep;
        if (!on_blocks) {
          if (const auto p = free_on(x, y, map.bounds.min.z())) return p;
          continue;
        }
        std::vector<double> tops;
        for (const Box& box : map.boxes) {
          if (x >= box.extent.min.x() && x <= box.extent.max.x() && y >= box.extent.min.y() &&
              y <= box.extent.max.y()) {
            tops.push_back(box.extent.max.z());
          }
        }
        std::sort(tops.begin(), tops.end());
        for (const double top : tops) {
          if (const auto p = free_on(x, y, top)) return p;
        }
      }
    }
  }
  return std::nullopt;
}

}  // namespace aerobox
