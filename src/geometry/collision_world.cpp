#include "geometry/collision_world.h"

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/narrowphase/collision_object.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/number_format.h"

namespace aerobox {
namespace {

using Node = fcl::detail::NodeBase<fcl::AABBd>;

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

class CollisionWorld::Tree {
 public:
  explicit Tree(const std::vector<Aabb>& boxes) {
    objects_.reserve(boxes.size());
    std::vector<fcl::CollisionObjectd*> raw;
    for (size_t i = 0; i < boxes.size(); ++i) {
      const Vec3 size = boxes[i].Size();
      auto shape = std::make_shared<fcl::Boxd>(size.x(), size.y(), size.z());
      fcl::Transform3d pose = fcl::Transform3d::Identity();
      pose.translation() = boxes[i].Center();
      objects_.push_back(std::make_unique<fcl::CollisionObjectd>(shape, pose));
      // the index of the box travels with the object, so a leaf leads back to our Aabb
      objects_.back()->setUserData(reinterpret_cast<void*>(i));
      raw.push_back(objects_.back().get());
    }
    manager_.registerObjects(raw);
    manager_.setup();
    // the traversals below keep at most height + 1 nodes on a fixed stack; FCL builds a
    // balanced tree (about log2 of the box count), so this holds for any real map
    if (manager_.getTree().getMaxHeight() + 2 > kMaxStack) {
      throw std::length_error("CollisionWorld: FCL tree too deep for the traversal stack");
    }
  }

  static constexpr size_t kMaxStack = 128;

  const Node* root() const { return manager_.getTree().getRoot(); }
  static size_t Index(const Node* leaf) {
    return reinterpret_cast<size_t>(static_cast<fcl::CollisionObjectd*>(leaf->data)->getUserData());
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
      if ((node->bv.min_.array() > query.max.array()).any() ||
          (query.min.array() > node->bv.max_.array()).any()) {
        continue;
      }
      if (node->isLeaf()) {
        if (visit(Index(node))) return true;
      } else {
        stack[top++] = node->children[0];
        stack[top++] = node->children[1];
      }
    }
    return false;
  }

 private:
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects_;
  fcl::DynamicAABBTreeCollisionManagerd manager_;
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
  const Node* stack[Tree::kMaxStack];
  int top = 0;
  if (tree_->root() != nullptr) stack[top++] = tree_->root();
  while (top > 0) {
    const Node* node = stack[--top];
    const double bound =
        PointBoxDistance(p, node->bv.min_.array() + clearance, node->bv.max_.array() - clearance);
    if (bound >= best) continue;
    if (node->isLeaf()) {
      const Aabb& box = boxes_[Tree::Index(node)];
      best = std::min(best, PointBoxDistance(p, box.min - half, box.max + half));
      continue;
    }
    // nearer child last, so it is popped first and tightens `best` early
    const Node* first = node->children[0];
    const Node* second = node->children[1];
    const double d0 = PointBoxDistance(p, first->bv.min_, first->bv.max_);
    const double d1 = PointBoxDistance(p, second->bv.min_, second->bv.max_);
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
