#include "planning/rrt_star.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/number_format.h"
#include "common/stop.h"
#include "planning/informed_sampler.h"
#include "planning/nearest_neighbours.h"
#include "planning/path_simplify.h"

namespace aerobox {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The tree: nodes in vectors, linked by parent index; children as intrusive sibling lists so
// that a rewired node's subtree can be walked to update its costs.
struct Tree {
  std::vector<Vec3> points;
  std::vector<int> parent;
  std::vector<double> cost;  // path length from the root [m]
  std::vector<int> first_child;
  std::vector<int> next_sibling;

  int Add(const Vec3& p, int parent_index, double path_cost) {
    const int index = static_cast<int>(points.size());
    points.push_back(p);
    parent.push_back(parent_index);
    cost.push_back(path_cost);
    first_child.push_back(-1);
    next_sibling.push_back(-1);
    if (parent_index >= 0) Link(index, parent_index);
    return index;
  }

  void Link(int child, int new_parent) {
    parent[child] = new_parent;
    next_sibling[child] = first_child[new_parent];
    first_child[new_parent] = child;
  }

  void Unlink(int child) {
    int* slot = &first_child[parent[child]];
    while (*slot != child) slot = &next_sibling[*slot];
    *slot = next_sibling[child];
  }

  // Gives `node` a new parent and cost, and moves its whole subtree's costs along.
  void Reparent(int node, int new_parent, double new_cost, std::vector<int>* stack) {
    const double delta = new_cost - cost[node];
    Unlink(node);
    Link(node, new_parent);
    cost[node] = new_cost;
    stack->assign(1, node);
    while (!stack->empty()) {
      const int n = stack->back();
      stack->pop_back();
      for (int c = first_child[n]; c >= 0; c = next_sibling[c]) {
        cost[c] += delta;
        stack->push_back(c);
      }
    }
  }
};

// Whether a motion was checked: rewiring reuses what choosing the parent found.
enum class Checked : signed char { kUnknown, kValid, kInvalid };

class Planner {
 public:
  Planner(const Vec3& start, const Vec3& goal, const Aabb& bounds, const Validity& validity,
          const RrtStarParams& params)
      : start_(start),
        goal_(goal),
        validity_(validity),
        params_(params),
        sampler_(start, goal, bounds),
        rng_(params.seed),
        index_(&tree_.points) {
    step_ = params.max_step > 0 ? params.max_step : 0.2 * bounds.Size().norm();
    // k-nearest RRT*: k(n) = k_rrt log(n) neighbours with k_rrt > 2^(d+1) e (1 + 1/d) keeps
    // asymptotic optimality (Karaman and Frazzoli 2011; the bound OMPL 1.5 uses), d = 3
    k_rrt_ = params.rewire_factor * std::pow(2.0, 3 + 1) * std::exp(1.0) * (1.0 + 1.0 / 3.0);
  }

  PlanResult Run() {
    const auto begin = std::chrono::steady_clock::now();
    const auto elapsed = [&begin] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    };
    PlanResult result;
    if (!validity_.state(start_)) {
      result.status = PlanStatus::kStartInvalid;
      return result;
    }
    if (!validity_.state(goal_)) {
      result.status = PlanStatus::kGoalInvalid;
      return result;
    }
    AddNode(start_, -1, 0.0);
    // a goal in plain sight is reached at once, however far (the straight line is optimal)
    if (validity_.motion(start_, goal_)) goal_parents_.push_back(0);
    UpdateBest(elapsed(), &result.stats);

    std::uniform_real_distribution<double> unit(0.0, 1.0);
    long& iterations = result.stats.iterations;
    long searched = 0;  // iterations before the first solution
    const auto more = [&] {
      ThrowIfStopRequested([&] {
        return "planning the path (RRT*, " + std::to_string(iterations) + " iterations)";
      });
      if (elapsed() >= params_.time_budget) {
        result.stats.time_capped = true;
        return false;
      }
      if (best_parent_ < 0) {
        return params_.max_search_iterations == 0 || searched < params_.max_search_iterations;
      }
      return !params_.stop_at_first_solution &&
             (params_.max_iterations == 0 || iterations - searched < params_.max_iterations);
    };
    while (more()) {
      if (best_parent_ < 0) ++searched;
      ++iterations;
      const Vec3 target = unit(rng_) < params_.goal_bias
                              ? goal_
                              : (params_.informed ? sampler_.Sample(best_cost_, &rng_)
                                                  : sampler_.Sample(kInf, &rng_));
      if (Extend(target)) UpdateBest(elapsed(), &result.stats);
    }
    result.stats.nodes = tree_.points.size();
    result.tree = std::move(grown_);
    if (best_parent_ < 0) {
      result.stats.planning_time = elapsed();
      return result;
    }

    result.status = PlanStatus::kSolved;
    for (int n = best_parent_; n >= 0; n = tree_.parent[n]) result.path.push_back(tree_.points[n]);
    std::reverse(result.path.begin(), result.path.end());
    if (result.path.back() != goal_) result.path.push_back(goal_);
    result.stats.tree_cost = PathLength(result.path);
    PruneWaypoints(validity_, &result.path);
    ShortcutPath(validity_, params_.shortcut_attempts, &rng_, &result.path);
    result.stats.final_cost = PathLength(result.path);
    result.stats.planning_time = elapsed();
    return result;
  }

 private:
  int AddNode(const Vec3& p, int parent, double cost) {
    const int index = tree_.Add(p, parent, cost);
    index_.Added();
    if (params_.record_tree && parent >= 0) grown_.emplace_back(p, tree_.points[parent]);
    return index;
  }

  // One RRT* extension towards `target`; returns whether the best path may have changed.
  bool Extend(const Vec3& target) {
    // steer from the nearest node
    index_.KNearest(target, 1, &neighbour_ids_, &neighbour_d2_);
    const Vec3& from = tree_.points[neighbour_ids_[0]];
    const double distance = std::sqrt(neighbour_d2_[0]);
    if (distance < 1e-9) return false;
    const Vec3 x = distance > step_ ? Vec3(from + (target - from) * (step_ / distance)) : target;
    if (!validity_.state(x)) return false;

    // the k nearest nodes, cheapest-through first
    const size_t n = tree_.points.size();
    const size_t k = std::min(n, static_cast<size_t>(std::ceil(k_rrt_ * std::log(n + 1.0))));
    index_.KNearest(x, k, &neighbour_ids_, &neighbour_d2_);
    candidates_.clear();
    for (size_t i = 0; i < neighbour_ids_.size(); ++i) {
      const int node = static_cast<int>(neighbour_ids_[i]);
      const double d = std::sqrt(neighbour_d2_[i]);
      candidates_.push_back({tree_.cost[node] + d, node, d, Checked::kUnknown});
    }
    // choose the parent: the cheapest neighbour with a valid motion; a heap yields them in
    // order of cost without sorting all (the first one is usually valid)
    const auto costlier = [](const Candidate& a, const Candidate& b) {
      return a.through > b.through;
    };
    std::make_heap(candidates_.begin(), candidates_.end(), costlier);
    int parent = -1;
    double cost = kInf;
    for (auto end = candidates_.end(); end != candidates_.begin(); --end) {
      std::pop_heap(candidates_.begin(), end, costlier);
      Candidate& c = *(end - 1);
      c.checked = validity_.motion(tree_.points[c.node], x) ? Checked::kValid : Checked::kInvalid;
      if (c.checked == Checked::kValid) {
        parent = c.node;
        cost = c.through;
        break;
      }
    }
    if (parent < 0) return false;
    const int added = AddNode(x, parent, cost);

    // rewire: neighbours that are cheaper to reach through the new node
    bool changed = false;
    for (Candidate& c : candidates_) {
      if (c.node == parent || cost + c.distance >= tree_.cost[c.node] - 1e-12) continue;
      if (c.checked == Checked::kUnknown) {
        c.checked = validity_.motion(x, tree_.points[c.node]) ? Checked::kValid : Checked::kInvalid;
      }
      if (c.checked != Checked::kValid) continue;
      tree_.Reparent(c.node, added, cost + c.distance, &stack_);
      changed = true;
    }
    return TryConnectGoal(added) || (changed && best_parent_ >= 0);
  }

  // Records `node` as a way to the goal when it sees the goal within one step.
  bool TryConnectGoal(int node) {
    const Vec3& p = tree_.points[node];
    if ((p - goal_).norm() > step_ || !validity_.motion(p, goal_)) return false;
    goal_parents_.push_back(node);
    return true;
  }

  void UpdateBest(double now, PlanStats* stats) {
    const int before = best_parent_;
    const double before_cost = best_cost_;
    for (const int node : goal_parents_) {
      const double c = tree_.cost[node] + (tree_.points[node] - goal_).norm();
      if (c < best_cost_ - 1e-12) {
        best_cost_ = c;
        best_parent_ = node;
      }
    }
    if (best_parent_ < 0 || (best_parent_ == before && best_cost_ == before_cost)) return;
    if (before < 0) {
      stats->time_to_first_solution = now;
      stats->iterations_to_first_solution = stats->iterations;
      stats->first_cost = best_cost_;
    }
    stats->cost_history.emplace_back(now, best_cost_);
  }

  struct Candidate {
    double through;  // cost of reaching the new point through this node [m]
    int node;
    double distance;
    Checked checked;
  };

  Vec3 start_;
  Vec3 goal_;
  const Validity& validity_;
  RrtStarParams params_;
  InformedSampler sampler_;
  std::mt19937_64 rng_;
  Tree tree_;
  NearestNeighbours index_;
  double step_ = 0.0;
  double k_rrt_ = 0.0;
  std::vector<int> goal_parents_;
  int best_parent_ = -1;
  double best_cost_ = kInf;
  // buffers reused across iterations
  std::vector<size_t> neighbour_ids_;
  std::vector<double> neighbour_d2_;
  std::vector<Candidate> candidates_;
  std::vector<int> stack_;
  std::vector<std::pair<Vec3, Vec3>> grown_;  // with params_.record_tree
};

}  // namespace

void RrtStarParams::Describe(Archive& a) {
  a.Integer({"max_iterations", "", "RRT* samples after the first solution (0: only time_budget)"},
            &max_iterations, 0, 100000000);
  a.Integer({"max_search_iterations", "", "RRT* samples for a first solution (then the lattice)"},
            &max_search_iterations, 0, 100000000);
  a.Number({"time_budget", "s", "wall-time cap of one search"}, &time_budget, 1e-3, 3600);
  a.Number({"max_step", "m", "longest edge the tree grows in one step (0: 0.2 x the diagonal)"},
           &max_step, 0, 1e4);
  a.Number({"goal_bias", "", "probability of steering at the goal"}, &goal_bias, 0, 0.99);
  a.Number({"rewire_factor", "", "scales the rewiring neighbourhood"}, &rewire_factor, 0.01, 100);
  a.Boolean({"informed", "", "sample only where the path can still improve"}, &informed);
  a.Integer({"shortcut_attempts", "", "random shortcuts tried on the returned path"},
            &shortcut_attempts, 0, 1000000);
}

void RrtStarParams::Validate() const {
  const auto fail = [](const char* field, double value) {
    throw std::invalid_argument(std::string("RrtStarParams.") + field +
                                " out of range: " + FormatNumber(value));
  };
  if (!(std::isfinite(max_step) && max_step >= 0)) fail("max_step", max_step);
  if (!(goal_bias >= 0 && goal_bias < 1)) fail("goal_bias", goal_bias);
  if (!(std::isfinite(rewire_factor) && rewire_factor > 0)) fail("rewire_factor", rewire_factor);
  if (!(time_budget > 0)) fail("time_budget", time_budget);
  if (max_iterations < 0) fail("max_iterations", static_cast<double>(max_iterations));
  if (max_search_iterations < 0) {
    fail("max_search_iterations", static_cast<double>(max_search_iterations));
  }
  if (shortcut_attempts < 0) fail("shortcut_attempts", shortcut_attempts);
}

PlanResult PlanRrtStar(const Vec3& start, const Vec3& goal, const Aabb& bounds,
                       const Validity& validity, const RrtStarParams& params) {
  params.Validate();
  if (!(bounds.min.array() <= bounds.max.array()).all()) {
    throw std::invalid_argument("PlanRrtStar: empty sampling bounds");
  }
  return Planner(start, goal, bounds, validity, params).Run();
}

}  // namespace aerobox
