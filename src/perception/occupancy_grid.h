// An occupancy map built in flight: a dense voxel grid over the map's bounds, each cell unknown
// until a depth ray passes through it (free) or ends in it (occupied), with OctoMap's log-odds
// update and clamping. A dense grid, not OctoMap's octree: our maps are bounded, so a grid gives
// O(1) cell access and a ray walk without tree descent (the navigation benchmark fuses the same
// frames 5x faster than OctoMap 1.9, for 4 times its memory). Fusion walks one ray per end
// cell: at 160 x 120 px, 25 Hz and 5 m it is about 46 % of a forest flight's wall time, the
// largest share.
#pragma once

#include <cstdint>
#include <set>
#include <vector>

#include "common/schema.h"
#include "common/types.h"
#include "perception/depth_camera.h"

namespace aerobox {

struct OccupancyParams {
  double resolution = 0.1;  // [m] a cell's side
  // The planner's assumption about unknown cells directly above and below an occupied one: true
  // counts them occupied until a ray sees them free (what stands in our maps stands on the
  // floor or hangs from something; a camera with a 58 deg vertical field sees a near pillar only
  // in a band, and a planner that takes the rest of it as free flies over the band into it).
  bool columns = false;

  void Describe(Archive& a);  // [sensing] resolution (common/schema.h)
};

enum class Occupancy : std::uint8_t { kUnknown, kFree, kOccupied };

class OccupancyGrid {
 public:
  // Cells over `bounds` [m]; throws std::invalid_argument naming `table`.resolution when the
  // grid would pass kMaxCells.
  OccupancyGrid(const Aabb& bounds, const OccupancyParams& params, const char* table = "sensing");

  // Fuses one frame: every returning pixel's ray marks the cells it crosses free and the cell
  // it ends in occupied (a pixel that hit nothing in range marks its whole ray free up to
  // `range` [m]); each cell changes at most once per frame, occupied first, as OctoMap's
  // insertPointCloud does. Pixels whose `hit` is in `ignored` (boxes known already) clear the
  // space before them only. Returns how many cells became occupied.
  int Insert(const DepthImage& image, double range, const std::vector<bool>& ignored);

  Occupancy At(const Vec3& p) const;  // kUnknown outside the grid
  // The occupied cells merged into boxes (runs along z, then y, then x); with `columns`, each
  // run grown up and down through unknown cells (OccupancyParams::columns): what the planner
  // avoids.
  std::vector<Aabb> OccupiedBoxes(bool columns = false) const;
  long occupied_count() const { return occupied_; }
  long free_count() const { return free_; }
  long cell_count() const { return static_cast<long>(cells_.size()); }
  double resolution() const { return resolution_; }
  long memory() const;  // [bytes] the cells, their walk stamps and the kept column runs
  Aabb CellBox(long index) const;

  static constexpr long kMaxCells = 200'000'000;

 private:
  long Index(int ix, int iy, int iz) const { return (static_cast<long>(ix) * ny_ + iy) * nz_ + iz; }
  bool CellOf(const Vec3& p, int* ix, int* iy, int* iz) const;
  // Marks the cells the segment a -> b crosses as free this frame (the end's own cell too when
  // `include_end`).
  void Clear(const Vec3& a, const Vec3& b, bool include_end);
  void Update(long index, float change);

  Aabb bounds_;
  double resolution_;
  int nx_ = 0, ny_ = 0, nz_ = 0;
  struct Cell {
    float log_odds = 0.0f;    // 0 and never stamped: unknown
    std::uint32_t stamp = 0;  // the frame that last changed it (0: no ray touched it yet)
  };
  std::vector<Cell> cells_;
  std::uint32_t frame_ = 0;
  // OccupiedBoxes's first step, kept per column (ix, iy) and redone only for the columns whose
  // cells changed state since (their occupancy, or unknown to known)
  using Runs = std::vector<std::pair<int, int>>;  // z-runs of a column, grown, in order
  Runs ColumnRuns(long column, bool columns) const;
  mutable std::vector<Runs> column_runs_;
  mutable std::vector<std::uint8_t> column_dirty_;
  mutable std::vector<long> dirty_columns_;
  mutable std::set<long> columns_with_runs_;  // sorted
  mutable int runs_grown_ = -1;               // the `columns` they were made with (-1: none)
  std::vector<Vec3> ends_;                    // this frame's: each pixel's ray's end [m]
  // per cell, the last frame a ray ending there was walked (frame << 2), with a bit for a ray
  // that hit a surface (1) and one for a ray to the range (2)
  std::vector<std::uint32_t> walked_;
  long occupied_ = 0, free_ = 0;
};

}  // namespace aerobox
