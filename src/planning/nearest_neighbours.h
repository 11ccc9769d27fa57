// k-nearest-neighbour search over a growing set of points, for RRT*: a static nanoflann k-d tree
// over most points plus a linear scan of the points added since it was built. The tree is
// rebuilt when that tail outgrows a fraction of it, so insertion costs O(log n) amortised and a
// query visits one tree (nanoflann's dynamic index keeps up to log2(n) trees and searches all of
// them, which is slow for the hundreds of neighbours RRT* asks for).
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include "common/types.h"

namespace aerobox {

class NearestNeighbours {
 public:
  // `points` is owned by the caller and only grows; call Added() after each push_back.
  explicit NearestNeighbours(const std::vector<Vec3>* points);
  ~NearestNeighbours();

  void Added();

  // Indices of the min(k, size) nearest points to q, in no particular order; exact.
  void KNearest(const Vec3& q, size_t k, std::vector<size_t>* indices,
                std::vector<double>* squared_distances) const;

 private:
  struct Index;  // nanoflann types stay in the .cpp
  void Rebuild();

  const std::vector<Vec3>* points_;
  std::unique_ptr<Index> index_;
  size_t indexed_ = 0;  // points [0, indexed_) are in the tree, the rest in the tail
  // query scratch space and the last large query's k-th distance [m] (not thread-safe)
  mutable std::vector<std::pair<double, size_t>> heap_;
  mutable std::vector<std::pair<size_t, double>> in_radius_;
  mutable double last_kth_distance_ = 0.0;
};

}  // namespace aerobox
