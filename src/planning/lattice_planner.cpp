#include "planning/lattice_planner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <queue>
#include <random>
#include <stdexcept>
#include <unordered_map>

#include "common/number_format.h"
#include "common/stop.h"
#include "planning/path_simplify.h"

namespace aerobox {
namespace {

// The 26 neighbour offsets; direction d and 25 - d are opposite.
struct Offsets {
  int d[26][3];
  Offsets() {
    int n = 0;
    for (int k = -1; k <= 1; ++k)
      for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i)
          if (i != 0 || j != 0 || k != 0) {
            d[n][0] = i;
            d[n][1] = j;
            d[n][2] = k;
            ++n;
          }
  }
};
const Offsets kOffsets;

double Elapsed(std::chrono::steady_clock::time_point begin) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
}

}  // namespace

void LatticeParams::Validate() const {
  const auto fail = [](const char* field, double value, const char* expected) {
    throw std::invalid_argument(std::string("LatticeParams.") + field + " must be " + expected +
                                ", got " + FormatNumber(value));
  };
  if (!(spacing > 0 && std::isfinite(spacing))) fail("spacing", spacing, "> 0");
  if (!(vertical_spacing > 0 && std::isfinite(vertical_spacing))) {
    fail("vertical_spacing", vertical_spacing, "> 0");
  }
  if (!std::isfinite(min_altitude)) fail("min_altitude", min_altitude, "finite");
  if (!(max_altitude >= min_altitude && std::isfinite(max_altitude))) {
    fail("max_altitude", max_altitude, ">= min_altitude");
  }
  if (shortcut_attempts < 0) fail("shortcut_attempts", shortcut_attempts, ">= 0");
}

LatticePlanner::LatticePlanner(const Aabb& bounds, const Validity& validity,
                               const LatticeParams& params)
    : validity_(validity), params_(params), bounds_(bounds) {
  params_.Validate();
  const auto begin = std::chrono::steady_clock::now();
  const double low = std::max(bounds.min.z(), params.min_altitude);
  const double high = std::min(bounds.max.z(), params.max_altitude);
  origin_ = Vec3(bounds.min.x(), bounds.min.y(), low);
  nx_ = static_cast<int>(std::floor((bounds.max.x() - bounds.min.x()) / params.spacing)) + 1;
  ny_ = static_cast<int>(std::floor((bounds.max.y() - bounds.min.y()) / params.spacing)) + 1;
  nz_ = high >= low ? static_cast<int>(std::floor((high - low) / params.vertical_spacing)) + 1 : 0;
  const size_t cells = static_cast<size_t>(nx_) * ny_ * nz_;
  free_.assign(cells, 0);
  links_.assign(cells, 0);
  for (size_t c = 0; c < cells; ++c) {
    ThrowIfStopRequested("building the planning lattice");
    free_[c] = validity_.state(Point(static_cast<int>(c)));
    stats_.nodes += free_[c];
  }
  // each pair of neighbours is checked once, from the cell with the lower index
  for (int k = 0; k < nz_; ++k) {
    for (int j = 0; j < ny_; ++j) {
      for (int i = 0; i < nx_; ++i) {
        const int c = Index(i, j, k);
        if (!free_[c]) continue;
        ThrowIfStopRequested("building the planning lattice");
        for (int d = 13; d < 26; ++d) {  // the "forward" half: higher indices
          const int a = i + kOffsets.d[d][0], b = j + kOffsets.d[d][1], e = k + kOffsets.d[d][2];
          if (a < 0 || b < 0 || e < 0 || a >= nx_ || b >= ny_ || e >= nz_) continue;
          const int n = Index(a, b, e);
          if (!free_[n] || !validity_.motion(Point(c), Point(n))) continue;
          links_[c] |= 1u << d;
          links_[n] |= 1u << (25 - d);
          ++stats_.edges;
        }
      }
    }
  }
  stats_.build_time = Elapsed(begin);
}

Vec3 LatticePlanner::Point(int index) const {
  const int i = index % nx_;
  const int j = (index / nx_) % ny_;
  const int k = index / (nx_ * ny_);
  return origin_ + Vec3(i * params_.spacing, j * params_.spacing, k * params_.vertical_spacing);
}

std::vector<int> LatticePlanner::Entries(const Vec3& p) const {
  const Vec3 cell =
      (p - origin_).cwiseQuotient(Vec3(params_.spacing, params_.spacing, params_.vertical_spacing));
  std::vector<int> entries;
  // the nearest cells first; widen the search (up to 4 cells) while none is visible, for
  // points in narrow places between buildings
  for (int reach = 1; reach <= 4 && entries.empty(); ++reach) {
    std::vector<std::pair<double, int>> near;
    for (int k = static_cast<int>(std::floor(cell.z())) - reach + 1;
         k <= static_cast<int>(std::floor(cell.z())) + reach; ++k) {
      for (int j = static_cast<int>(std::floor(cell.y())) - reach + 1;
           j <= static_cast<int>(std::floor(cell.y())) + reach; ++j) {
        for (int i = static_cast<int>(std::floor(cell.x())) - reach + 1;
             i <= static_cast<int>(std::floor(cell.x())) + reach; ++i) {
          if (i < 0 || j < 0 || k < 0 || i >= nx_ || j >= ny_ || k >= nz_) continue;
          const int c = Index(i, j, k);
          if (free_[c]) near.emplace_back((Point(c) - p).norm(), c);
        }
      }
    }
    std::sort(near.begin(), near.end());
    for (const auto& [distance, c] : near) {
      if (validity_.motion(p, Point(c))) entries.push_back(c);
      if (entries.size() >= 4) break;  // a few ways in are plenty
    }
  }
  return entries;
}

std::vector<LatticePlanner::Way> LatticePlanner::Ways(const Vec3& p) const {
  std::vector<Way> ways;
  for (const int c : Entries(p)) ways.push_back({c, false, p, (Point(c) - p).norm()});
  if (!ways.empty()) return ways;
  // no lattice point in sight: climb or descend in half-level steps, the nearest first, until a
  // point on the way sees the lattice (a motion blocked at one height is blocked above it too)
  bool up = true;
  bool down = true;
  for (double h = 0.5 * params_.vertical_spacing; (up || down) && ways.empty();
       h += 0.5 * params_.vertical_spacing) {
    for (const double sign : {1.0, -1.0}) {
      bool& open = sign > 0 ? up : down;
      if (!open) continue;
      const Vec3 q = p + sign * h * Vec3::UnitZ();
      if (q.z() > bounds_.max.z() || q.z() < bounds_.min.z() || !validity_.motion(p, q)) {
        open = false;
        continue;
      }
      for (const int c : Entries(q)) ways.push_back({c, true, q, h + (Point(c) - q).norm()});
    }
  }
  return ways;
}

PlanResult LatticePlanner::Plan(const Vec3& start, const Vec3& goal) const {
  const auto begin = std::chrono::steady_clock::now();
  PlanResult result;
  if (!validity_.state(start)) {
    result.status = PlanStatus::kStartInvalid;
    return result;
  }
  if (!validity_.state(goal)) {
    result.status = PlanStatus::kGoalInvalid;
    return result;
  }
  if (validity_.motion(start, goal)) {  // in plain sight
    result.status = PlanStatus::kSolved;
    result.path = {start, goal};
  } else {
    // per entry cell, the best way in from the start and out to the goal
    std::unordered_map<int, Way> sources;
    std::unordered_map<int, Way> targets;
    for (const Way& way : Ways(start)) {
      auto [it, added] = sources.emplace(way.cell, way);
      if (!added && way.length < it->second.length) it->second = way;
    }
    for (const Way& way : Ways(goal)) {
      auto [it, added] = targets.emplace(way.cell, way);
      if (!added && way.length < it->second.length) it->second = way;
    }
    // A* over the lattice from every entry near the start to any entry near the goal (the
    // last leg's length is part of the cost, so the best way out is chosen)
    const size_t cells = free_.size();
    std::vector<double> cost(cells, std::numeric_limits<double>::infinity());
    std::vector<int> parent(cells, -1);
    std::vector<double> exit_cost(cells, -1.0);
    for (const auto& [t, way] : targets) exit_cost[t] = way.length;
    using Item = std::pair<double, int>;  // (cost + heuristic, cell)
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
    for (const auto& [s, way] : sources) {
      cost[s] = way.length;
      open.emplace(cost[s] + (Point(s) - goal).norm(), s);
    }
    int reached = -1;
    double best = std::numeric_limits<double>::infinity();
    while (!open.empty()) {
      const auto [estimate, c] = open.top();
      open.pop();
      if (estimate >= best) break;  // nothing left can do better (the heuristic is admissible)
      if (estimate > cost[c] + (Point(c) - goal).norm() + 1e-9) continue;  // stale entry
      ++result.stats.iterations;
      ThrowIfStopRequested("planning the path (a lattice search)");
      if (exit_cost[c] >= 0 && cost[c] + exit_cost[c] < best) {
        best = cost[c] + exit_cost[c];
        reached = c;
      }
      const Vec3 p = Point(c);
      for (int d = 0; d < 26; ++d) {
        if (!(links_[c] & (1u << d))) continue;
        const int n = c + (kOffsets.d[d][2] * ny_ + kOffsets.d[d][1]) * nx_ + kOffsets.d[d][0];
        const double through = cost[c] + (Point(n) - p).norm();
        if (through < cost[n]) {
          cost[n] = through;
          parent[n] = c;
          open.emplace(through + (Point(n) - goal).norm(), n);
        }
      }
    }
    if (reached < 0) {
      result.stats.planning_time = Elapsed(begin);
      return result;
    }
    result.status = PlanStatus::kSolved;
    result.path = {goal};
    if (targets.at(reached).has_via) result.path.push_back(targets.at(reached).via);
    int first = reached;
    for (int c = reached; c >= 0; c = parent[c]) {
      result.path.push_back(Point(c));
      first = c;
    }
    if (sources.at(first).has_via) result.path.push_back(sources.at(first).via);
    result.path.push_back(start);
    std::reverse(result.path.begin(), result.path.end());
  }
  result.stats.first_cost = result.stats.tree_cost = PathLength(result.path);
  result.stats.time_to_first_solution = Elapsed(begin);
  PruneWaypoints(validity_, &result.path);
  std::mt19937_64 rng(params_.seed);
  ShortcutPath(validity_, params_.shortcut_attempts, &rng, &result.path);
  result.stats.final_cost = PathLength(result.path);
  result.stats.nodes = stats_.nodes;
  result.stats.planning_time = Elapsed(begin);
  return result;
}

}  // namespace aerobox
