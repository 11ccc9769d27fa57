// Long queries (a city): a lattice over free space built once, searched with A* per query,
// then pruned and shortcut against the same validity (the FCND seed study's approach: global
// graph, local refinement). Build and query times are reported separately.
#pragma once

#include <cstdint>
#include <vector>

#include "common/types.h"
#include "planning/plan_result.h"
#include "planning/validity.h"

namespace aerobox {

struct LatticeParams {
  double spacing = 10.0;           // [m] between lattice points along x and y
  double vertical_spacing = 10.0;  // [m] between altitude levels
  double min_altitude = 10.0;      // [m] world z of the lowest level
  double max_altitude = 60.0;      // [m] world z of the highest level (at most)
  int shortcut_attempts = 200;     // random shortcuts on the found path
  std::uint64_t seed = 1;          // for the shortcuts

  void Validate() const;
};

struct LatticeStats {
  size_t nodes = 0;         // free lattice points
  size_t edges = 0;         // free straight connections between neighbours (26-connected)
  double build_time = 0.0;  // [s]
};

class LatticePlanner {
 public:
  // Builds the lattice inside `bounds`: the free points and which of their 26 neighbours they
  // see. Throws std::invalid_argument for bad parameters.
  LatticePlanner(const Aabb& bounds, const Validity& validity, const LatticeParams& params);

  const LatticeStats& stats() const { return stats_; }

  // start and goal join the lattice at the nearest visible points (within four spacings); a
  // point that sees none (a narrow shaft between buildings, with no lattice point inside)
  // climbs or descends straight until it does. A* finds the shortest lattice path; pruning
  // and shortcuts straighten it. Statuses as RRT*'s;
  // stats.planning_time is the query's time, stats.iterations the nodes A* expanded.
  PlanResult Plan(const Vec3& start, const Vec3& goal) const;

 private:
  int Index(int i, int j, int k) const { return (k * ny_ + j) * nx_ + i; }
  Vec3 Point(int index) const;
  // lattice points near p that a straight motion from p reaches, nearest first
  std::vector<int> Entries(const Vec3& p) const;
  // A way between a point and the lattice: straight to `cell`, or first straight up or down
  // to `via` and from there straight to `cell`; `length` [m] is the whole way's.
  struct Way {
    int cell = -1;
    bool has_via = false;
    Vec3 via = Vec3::Zero();
    double length = 0.0;
  };
  // The ways for p: Entries(p), or else the nearest vertical detour that has entries.
  std::vector<Way> Ways(const Vec3& p) const;

  Validity validity_;
  LatticeParams params_;
  Aabb bounds_;
  Vec3 origin_;
  int nx_ = 0, ny_ = 0, nz_ = 0;
  std::vector<std::uint8_t> free_;    // per cell
  std::vector<std::uint32_t> links_;  // per cell: bit d set when neighbour d is reachable
  LatticeStats stats_;
};

}  // namespace aerobox
