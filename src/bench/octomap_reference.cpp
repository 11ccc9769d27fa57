#include "bench/octomap_reference.h"

#include <octomap/OcTree.h>

#include <cmath>

namespace aerobox {

struct OctoMapReference::Impl {
  explicit Impl(double resolution) : tree(resolution) {}
  octomap::OcTree tree;
  octomap::Pointcloud cloud;
};

OctoMapReference::OctoMapReference(double resolution) : impl_(std::make_unique<Impl>(resolution)) {}

OctoMapReference::~OctoMapReference() = default;

void OctoMapReference::Insert(const DepthImage& image, double range) {
  octomap::Pointcloud& cloud = impl_->cloud;
  cloud.clear();
  cloud.reserve(image.depth.size());
  for (int v = 0; v < image.height; ++v) {
    for (int u = 0; u < image.width; ++u) {
      const size_t k = static_cast<size_t>(v * image.width + u);
      Vec3 p;
      if (image.depth[k] > 0.0f) {
        p = image.PointW(u, v);
      } else if (image.hit[k] == kNoReturn) {
        p = image.origin_W + image.R_WC * image.RayC(u, v) * (range * 1.01);
      } else {
        continue;  // dropped
      }
      cloud.push_back(static_cast<float>(p.x()), static_cast<float>(p.y()),
                      static_cast<float>(p.z()));
    }
  }
  const Vec3& o = image.origin_W;
  impl_->tree.insertPointCloud(
      cloud,
      octomap::point3d(static_cast<float>(o.x()), static_cast<float>(o.y()),
                       static_cast<float>(o.z())),
      range, /*lazy_eval=*/false, /*discretize=*/true);
}

Occupancy OctoMapReference::At(const Vec3& p) const {
  const octomap::OcTreeNode* node = impl_->tree.search(p.x(), p.y(), p.z());
  if (node == nullptr) return Occupancy::kUnknown;
  return impl_->tree.isNodeOccupied(node) ? Occupancy::kOccupied : Occupancy::kFree;
}

std::vector<Vec3> OctoMapReference::OccupiedCentres(const Aabb& bounds) const {
  const octomap::OcTree& tree = impl_->tree;
  const double r = tree.getResolution();
  std::vector<Vec3> centres;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    const double half = 0.5 * it.getSize();
    const Vec3 c(it.getX(), it.getY(), it.getZ());
    const int n = static_cast<int>(std::lround(it.getSize() / r));
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        for (int k = 0; k < n; ++k) {
          const Vec3 p = c - Vec3::Constant(half - 0.5 * r) + r * Vec3(i, j, k);
          if (bounds.Contains(p)) centres.push_back(p);
        }
      }
    }
  }
  return centres;
}

long OctoMapReference::memory() const { return static_cast<long>(impl_->tree.memoryUsage()); }

}  // namespace aerobox
