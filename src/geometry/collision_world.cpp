#include "geometry/collision_world.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/number_format.h"

namespace aerobox {
namespace {

// True when the open interior of `box` meets the closed segment a + t (b - a), t in [0, 1]
// (slab method: the segment's parameter interval inside each pair of faces, intersected).
bool SegmentEntersBox(const Vec3& a, const Vec3& b, const Aabb& box) {
  const Vec3 d = b - a;
  double enter = -std::numeric_limits<double>::infinity();
  double exit = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0.0) {
      if (!(box.min[k] < a[k] && a[k] < box.max[k])) return false;
      continue;
    }
    double t0 = (box.min[k] - a[k]) / d[k];
    double t1 = (box.max[k] - a[k]) / d[k];
    if (t0 > t1) std::swap(t0, t1);
    enter = std::max(enter, t0);
    exit = std::min(exit, t1);
  }
  // the open interval (enter, exit) meets [0, 1]
  return enter < exit && enter < 1.0 && exit > 0.0;
}

// Euclidean distance between a point and a box [m] (0 inside).
double PointBoxDistance(const Vec3& p, const Vec3& min, const Vec3& max) {
  return (min - p).cwiseMax(p - max).cwiseMax(0.0).norm();
}

}  // namespace

// A bounding volume hierarchy over the boxes, built once, top down: each node splits its boxes at
// the median of their centres along the longest side of the centres' extent, so the tree is
// balanced (depth about log2 of the box count) and its nodes lie in one array. A world is
// rebuilt at every depth frame that adds occupied cells: one allocation, not one per box.
class CollisionWorld::Tree {
 public:
  struct Node {
    Aabb bv;           // encloses every box below
    int children[2];   // indices into nodes_ (an inner node)
    size_t index = 0;  // a leaf's box
    bool leaf = false;
  };

  explicit Tree(const std::vector<Aabb>& boxes) {
    if (boxes.empty()) return;
    std::vector<size_t> order(boxes.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    nodes_.reserve(2 * boxes.size() - 1);
    Build(boxes, &order, 0, order.size());
  }

  static constexpr size_t kMaxStack = 128;  // a balanced tree of fewer than 2^120 boxes

  const Node* root() const { return nodes_.empty() ? nullptr : &nodes_[0]; }
  const Node* child(const Node* node, int k) const {
    return &nodes_[static_cast<size_t>(node->children[k])];
  }

  // Calls visit(index) for every box whose bounding box meets `query` (closed), until visit
  // returns true; returns whether it did.
  template <typename Visit>
  bool AnyCandidate(const Aabb& query, Visit&& visit) const {
    const Node* stack[Tree::kMaxStack];
    int top = 0;
    if (root() != nullptr) stack[top++] = root();
    while (top > 0) {
      const Node* node = stack[--top];
      if ((node->bv.min.array() > query.max.array()).any() ||
          (query.min.array() > node->bv.max.array()).any()) {
        continue;
      }
      if (node->leaf) {
        if (visit(node->index)) return true;
      } else {
        stack[top++] = child(node, 0);
        stack[top++] = child(node, 1);
      }
    }
    return false;
  }

 private:
  // The node over order[begin, end); returns its index.
  int Build(const std::vector<Aabb>& boxes, std::vector<size_t>* order, size_t begin, size_t end) {
    const int at = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    Aabb bv = boxes[(*order)[begin]];
    Vec3 lo = bv.Center(), hi = lo;
    for (size_t i = begin; i < end; ++i) {
      const Aabb& b = boxes[(*order)[i]];
      bv.min = bv.min.cwiseMin(b.min);
      bv.max = bv.max.cwiseMax(b.max);
      lo = lo.cwiseMin(b.Center());
      hi = hi.cwiseMax(b.Center());
    }
    nodes_[static_cast<size_t>(at)].bv = bv;
    if (end - begin == 1) {
      nodes_[static_cast<size_t>(at)].leaf = true;
      nodes_[static_cast<size_t>(at)].index = (*order)[begin];
      return at;
    }
    int axis;
    (hi - lo).maxCoeff(&axis);
    const size_t middle = begin + (end - begin) / 2;
    // by centre, then by index: the same boxes give the same tree
    std::nth_element(order->begin() + static_cast<long>(begin),
                     order->begin() + static_cast<long>(middle),
                     order->begin() + static_cast<long>(end), [&](size_t a, size_t b) {
                       const double ca = boxes[a].min[axis] + boxes[a].max[axis];
                       const double cb = boxes[b].min[axis] + boxes[b].max[axis];
                       return ca < cb || (ca == cb && a < b);
                     });
    const int left = Build(boxes, order, begin, middle);
    const int right = Build(boxes, order, middle, end);
    nodes_[static_cast<size_t>(at)].children[0] = left;
    nodes_[static_cast<size_t>(at)].children[1] = right;
    return at;
  }

  std::vector<Node> nodes_;
};

void CollisionParams::Validate() const {
  if (!(vehicle_size.allFinite() && (vehicle_size.array() > 0).all())) {
    throw std::invalid_argument("CollisionParams.vehicle_size must be positive, got " +
                                FormatVector(vehicle_size));
  }
  if (!(std::isfinite(clearance) && clearance >= 0)) {
    throw std::invalid_argument("CollisionParams.clearance must be >= 0, got " +
                                FormatNumber(clearance));
  }
}

CollisionWorld::CollisionWorld(const Map& map, const CollisionParams& params) : params_(params) {
  params_.Validate();
  const Vec3 margin = params_.Margin();
  free_bounds_ = {map.bounds.min + margin, map.bounds.max - margin};
  for (const Box& box : map.boxes) {
    boxes_.push_back(box.extent);
    grown_.push_back({box.extent.min - margin, box.extent.max + margin});
  }
  tree_ = std::make_unique<Tree>(grown_);
}

CollisionWorld::~CollisionWorld() = default;
CollisionWorld::CollisionWorld(CollisionWorld&&) noexcept = default;
CollisionWorld& CollisionWorld::operator=(CollisionWorld&&) noexcept = default;

bool CollisionWorld::IsPointFree(const Vec3& p) const {
  if (!p.allFinite() || !free_bounds_.Contains(p)) return false;
  return !tree_->AnyCandidate(Aabb{p, p}, [&](size_t i) {
    return (grown_[i].min.array() < p.array()).all() && (p.array() < grown_[i].max.array()).all();
  });
}

bool CollisionWorld::IsSegmentFree(const Vec3& a, const Vec3& b) const {
  // free_bounds_ is convex: both ends inside keeps the whole segment inside
  if (!IsPointFree(a) || !b.allFinite() || !free_bounds_.Contains(b)) return false;
  const Aabb span{a.cwiseMin(b), a.cwiseMax(b)};
  return !tree_->AnyCandidate(span, [&](size_t i) { return SegmentEntersBox(a, b, grown_[i]); });
}

bool CollisionWorld::IsBoxFree(const Aabb& box) const {
  if (!box.min.allFinite() || !box.max.allFinite() || !box.IsInside(free_bounds_)) return false;
  return !tree_->AnyCandidate(box, [&](size_t i) { return grown_[i].Overlaps(box); });
}

double CollisionWorld::Clearance(const Vec3& p) const {
  // distance between the vehicle's box at p and box i = distance from p to box i grown by the
  // vehicle's half-size; the tree holds boxes grown by half-size + clearance, so a tree node's
  // bounding box shrunk by the clearance still encloses its boxes: a lower bound for pruning
  const Vec3 half = 0.5 * params_.vehicle_size;
  const double clearance = params_.clearance;
  double best = std::numeric_limits<double>::infinity();
  using Node = Tree::Node;
  const Node* stack[Tree::kMaxStack];
  int top = 0;
  if (tree_->root() != nullptr) stack[top++] = tree_->root();
  while (top > 0) {
    const Node* node = stack[--top];
    const double bound =
        PointBoxDistance(p, node->bv.min.array() + clearance, node->bv.max.array() - clearance);
    if (bound >= best) continue;
    if (node->leaf) {
      const Aabb& box = boxes_[node->index];
      best = std::min(best, PointBoxDistance(p, box.min - half, box.max + half));
      continue;
    }
    // nearer child last, so it is popped first and tightens `best` early
    const Node* first = tree_->child(node, 0);
    const Node* second = tree_->child(node, 1);
    const double d0 = PointBoxDistance(p, first->bv.min, first->bv.max);
    const double d1 = PointBoxDistance(p, second->bv.min, second->bv.max);
    if (d0 < d1) std::swap(first, second);
    stack[top++] = first;
    stack[top++] = second;
  }
  return best;
}

std::optional<size_t> CollisionWorld::OverlappingBox(const Vec3& p) const {
  const Vec3 half = 0.5 * params_.vehicle_size;
  const Aabb vehicle{p - half, p + half};
  std::optional<size_t> found;
  tree_->AnyCandidate(vehicle, [&](size_t i) {
    if (boxes_[i].Overlaps(vehicle)) found = i;
    return found.has_value();
  });
  return found;
}

std::optional<size_t> CollisionWorld::BlockingBox(const Vec3& p) const {
  constexpr double kReach = 1e-3;  // [m] a point found by bisection sits at a surface
  const Vec3 reach = Vec3::Constant(kReach);
  std::optional<size_t> found;
  double nearest = kReach;
  tree_->AnyCandidate(Aabb{p - reach, p + reach}, [&](size_t i) {
    const Vec3 outside = (grown_[i].min - p).cwiseMax(p - grown_[i].max).cwiseMax(0.0);
    if (outside.norm() <= nearest) {
      nearest = outside.norm();
      found = i;
    }
    return false;  // every candidate: the nearest one
  });
  return found;
}

Projection CollisionWorld::ProjectIntoFreeBounds(const Vec3& p) const {
  const Vec3 q = p.cwiseMax(free_bounds_.min).cwiseMin(free_bounds_.max);
  return {q, (q - p).norm()};
}

}  // namespace aerobox
