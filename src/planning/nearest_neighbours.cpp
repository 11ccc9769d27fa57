#include "planning/nearest_neighbours.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nanoflann.hpp>

namespace aerobox {
namespace {

// nanoflann's view of the first `count` points.
struct Cloud {
  const std::vector<Vec3>* points;
  size_t count = 0;
  size_t kdtree_get_point_count() const { return count; }
  double kdtree_get_pt(size_t i, size_t dim) const { return (*points)[i][static_cast<int>(dim)]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud,
                                                 3, size_t>;

// Keeps the k nearest points seen in a max-heap: O(log k) per accepted point, where nanoflann's
// KNNResultSet shifts an array (O(k)), which dominates for RRT*'s hundreds of neighbours.
// Implements nanoflann's result-set interface.
class HeapResultSet {
 public:
  explicit HeapResultSet(size_t k, std::vector<std::pair<double, size_t>>* heap)
      : k_(k), heap_(heap) {
    heap_->clear();
  }
  size_t size() const { return heap_->size(); }
  bool full() const { return heap_->size() == k_; }
  double worstDist() const {
    return full() ? heap_->front().first : std::numeric_limits<double>::max();
  }
  bool addPoint(double squared_distance, size_t index) {
    if (!full()) {
      heap_->emplace_back(squared_distance, index);
      std::push_heap(heap_->begin(), heap_->end());
    } else if (squared_distance < heap_->front().first) {
      std::pop_heap(heap_->begin(), heap_->end());
      heap_->back() = {squared_distance, index};
      std::push_heap(heap_->begin(), heap_->end());
    }
    return true;  // keep searching
  }

 private:
  size_t k_;
  std::vector<std::pair<double, size_t>>* heap_;
};

// Up to this many neighbours a heap is fastest; beyond, a radius search and a selection.
constexpr size_t kHeapQueryMax = 32;

// The tail may hold this many points, or a sixteenth of the tree, whichever is more: rebuilding
// costs O(n log n) every n/16 insertions, scanning the tail O(n/16) per query.
constexpr size_t kMinTail = 256;
constexpr size_t kTailFraction = 16;

}  // namespace

struct NearestNeighbours::Index {
  explicit Index(const std::vector<Vec3>* points)
      : cloud{points, 0},
        tree(3, cloud,
             nanoflann::KDTreeSingleIndexAdaptorParams(
                 10, nanoflann::KDTreeSingleIndexAdaptorFlags::SkipInitialBuildIndex)) {}
  Cloud cloud;
  Tree tree;
};

NearestNeighbours::NearestNeighbours(const std::vector<Vec3>* points)
    : points_(points), index_(std::make_unique<Index>(points)) {}

NearestNeighbours::~NearestNeighbours() = default;

void NearestNeighbours::Added() {
  const size_t tail = points_->size() - indexed_;
  if (tail > std::max(kMinTail, indexed_ / kTailFraction)) Rebuild();
}

void NearestNeighbours::Rebuild() {
  index_->cloud.count = points_->size();
  index_->tree.buildIndex();
  indexed_ = points_->size();
}

void NearestNeighbours::KNearest(const Vec3& q, size_t k, std::vector<size_t>* indices,
                                 std::vector<double>* squared_distances) const {
  indices->clear();
  squared_distances->clear();
  k = std::min(k, points_->size());
  if (k == 0) return;
  const std::vector<Vec3>& points = *points_;
  if (k <= kHeapQueryMax || !(last_kth_distance_ > 0)) {
    // few neighbours (or no radius to start from): keep the best k in a heap
    HeapResultSet result(k, &heap_);
    if (indexed_ > 0) index_->tree.findNeighbors(result, q.data(), nanoflann::SearchParams());
    for (size_t i = indexed_; i < points.size(); ++i) {
      const double d2 = (points[i] - q).squaredNorm();
      if (d2 < result.worstDist()) result.addPoint(d2, i);
    }
    if (k > kHeapQueryMax) last_kth_distance_ = std::sqrt(heap_.front().first);
  } else {
    // many neighbours: gather everything within a radius guessed from the previous query
    // (growing it until at least k points fall inside), then select the k nearest
    double radius = 1.2 * last_kth_distance_;
    while (true) {
      in_radius_.clear();
      if (indexed_ > 0) {
        nanoflann::RadiusResultSet<double, size_t> result(radius * radius, in_radius_);
        index_->tree.findNeighbors(result, q.data(), nanoflann::SearchParams());
      }
      for (size_t i = indexed_; i < points.size(); ++i) {
        const double d2 = (points[i] - q).squaredNorm();
        if (d2 < radius * radius) in_radius_.emplace_back(i, d2);
      }
      if (in_radius_.size() >= k) break;
      radius *= 1.6;  // about 4x the volume
    }
    const auto by_distance = [](const std::pair<size_t, double>& a,
                                const std::pair<size_t, double>& b) {
      return a.second < b.second || (a.second == b.second && a.first < b.first);
    };
    std::nth_element(in_radius_.begin(), in_radius_.begin() + static_cast<long>(k - 1),
                     in_radius_.end(), by_distance);
    last_kth_distance_ = std::sqrt(in_radius_[k - 1].second);
    for (size_t i = 0; i < k; ++i) {
      indices->push_back(in_radius_[i].first);
      squared_distances->push_back(in_radius_[i].second);
    }
    return;
  }
  for (const auto& [d2, index] : heap_) {
    indices->push_back(index);
    squared_distances->push_back(d2);
  }
}

}  // namespace aerobox
