#include "planning/path_simplify.h"

#include <algorithm>
#include <limits>

namespace aerobox {
namespace {

// The point at arc length s along the path, and the index of the segment it lies on.
std::pair<Vec3, size_t> PointAt(const std::vector<Vec3>& path, const std::vector<double>& arc,
                                double s) {
  size_t i = 0;
  while (i + 2 < path.size() && arc[i + 1] < s) ++i;
  const double length = arc[i + 1] - arc[i];
  const double t = length > 0 ? std::clamp((s - arc[i]) / length, 0.0, 1.0) : 0.0;
  return {path[i] + t * (path[i + 1] - path[i]), i};
}

}  // namespace

double PathLength(const std::vector<Vec3>& path) {
  double length = 0.0;
  for (size_t i = 1; i < path.size(); ++i) length += (path[i] - path[i - 1]).norm();
  return length;
}

std::vector<Vec3> PathHead(const std::vector<Vec3>& path, double arc) {
  std::vector<Vec3> head = {path.front()};
  for (size_t i = 1; i < path.size(); ++i) {
    const double length = (path[i] - path[i - 1]).norm();
    if (arc < length) {
      head.push_back(path[i - 1] + (arc / length) * (path[i] - path[i - 1]));
      return head;
    }
    arc -= length;
    head.push_back(path[i]);
  }
  return head;
}

double ArcNearest(const std::vector<Vec3>& path, const Vec3& p) {
  double arc = 0.0, here = 0.0, nearest = std::numeric_limits<double>::infinity();
  for (size_t i = 1; i < path.size(); ++i) {
    const Vec3 d = path[i] - path[i - 1];
    const double length = d.norm();
    const double along =
        length > 0 ? std::clamp((p - path[i - 1]).dot(d) / (length * length), 0.0, 1.0) : 0.0;
    const double distance = (path[i - 1] + along * d - p).norm();
    if (distance < nearest) {
      nearest = distance;
      here = arc + along * length;
    }
    arc += length;
  }
  return here;
}

void ShortcutPath(const Validity& validity, int attempts, std::mt19937_64* rng,
                  std::vector<Vec3>* path) {
  std::vector<double> arc;
  for (int attempt = 0; attempt < attempts && path->size() > 2; ++attempt) {
    arc.assign(1, 0.0);
    for (size_t i = 1; i < path->size(); ++i)
      arc.push_back(arc.back() + ((*path)[i] - (*path)[i - 1]).norm());
    std::uniform_real_distribution<double> along(0.0, arc.back());
    double s0 = along(*rng);
    double s1 = along(*rng);
    if (s0 > s1) std::swap(s0, s1);
    const auto [p0, i0] = PointAt(*path, arc, s0);
    const auto [p1, i1] = PointAt(*path, arc, s1);
    if (i0 == i1) continue;  // on one segment already straight
    // the new piece must be shorter than what it replaces, by more than rounding
    const double replaced = s1 - s0;
    if ((p1 - p0).norm() >= replaced - 1e-9 || !validity.motion(p0, p1)) continue;
    std::vector<Vec3> shorter(path->begin(), path->begin() + static_cast<long>(i0) + 1);
    shorter.push_back(p0);
    shorter.push_back(p1);
    shorter.insert(shorter.end(), path->begin() + static_cast<long>(i1) + 1, path->end());
    path->swap(shorter);
    PruneWaypoints(validity, path);
  }
}

void PruneWaypoints(const Validity& validity, std::vector<Vec3>* path) {
  if (path->size() < 3) return;
  std::vector<Vec3> kept = {path->front()};
  for (size_t i = 1; i + 1 < path->size(); ++i) {
    if (validity.motion(kept.back(), (*path)[i + 1])) continue;
    kept.push_back((*path)[i]);
  }
  kept.push_back(path->back());
  path->swap(kept);
}

}  // namespace aerobox
