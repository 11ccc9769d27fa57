#include "perception/occupancy_grid.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>

namespace aerobox {
namespace {

// OctoMap's defaults: a hit says occupied with probability 0.7, a miss 0.4; clamped to
// [0.12, 0.97]; occupied above 0.5. As log-odds:
constexpr float kHit = 0.8473f;      // log(0.7 / 0.3)
constexpr float kMiss = -0.4055f;    // log(0.4 / 0.6)
constexpr float kLowest = -1.9924f;  // log(0.12 / 0.88)
constexpr float kHighest = 3.4761f;  // log(0.97 / 0.03)

}  // namespace

void OccupancyParams::Describe(Archive& a) {
  a.Number({"resolution", "m", "the occupancy map's cell side (kind \"depth\")"}, &resolution, 0.02,
           2);
  a.Boolean({"columns", "",
             "unknown cells above and below an occupied one count as occupied until seen free"},
            &columns);
}

OccupancyGrid::OccupancyGrid(const Aabb& bounds, const OccupancyParams& params, const char* table)
    : bounds_(bounds), resolution_(params.resolution) {
  const Vec3 cells = (bounds.Size() / resolution_).array().ceil().max(1.0);
  const double total = cells.prod();
  if (!(resolution_ > 0) || !(total <= static_cast<double>(kMaxCells))) {
    throw std::invalid_argument(std::string(table) + ".resolution: " + std::to_string(resolution_) +
                                " m would need " + std::to_string(total) +
                                " cells over the map's bounds (at most " +
                                std::to_string(kMaxCells) + ")");
  }
  nx_ = static_cast<int>(cells.x());
  ny_ = static_cast<int>(cells.y());
  nz_ = static_cast<int>(cells.z());
  const size_t n = static_cast<size_t>(total);
  cells_.assign(n, Cell());
  column_runs_.assign(static_cast<size_t>(nx_) * static_cast<size_t>(ny_), Runs());
  column_dirty_.assign(column_runs_.size(), 0);
}

bool OccupancyGrid::CellOf(const Vec3& p, int* ix, int* iy, int* iz) const {
  // clamped to the grid, so that a point on (or a rounding error outside) its faces has a cell
  const Vec3 c = ((p - bounds_.min) / resolution_).cwiseMax(0.0);
  *ix = static_cast<int>(std::min(c.x(), nx_ - 1.0));
  *iy = static_cast<int>(std::min(c.y(), ny_ - 1.0));
  *iz = static_cast<int>(std::min(c.z(), nz_ - 1.0));
  return bounds_.Contains(p);
}

Aabb OccupancyGrid::CellBox(long index) const {
  const long iz = index % nz_, iy = (index / nz_) % ny_,
             ix = index / (static_cast<long>(nz_) * ny_);
  const Vec3 min = bounds_.min + resolution_ * Vec3(ix, iy, iz);
  return {min, (min.array() + resolution_).matrix()};
}

long OccupancyGrid::memory() const {
  long bytes = static_cast<long>(cells_.capacity() * sizeof(Cell) +
                                 walked_.capacity() * sizeof(std::uint32_t) +
                                 column_runs_.capacity() * sizeof(Runs) + column_dirty_.capacity());
  for (const long c : columns_with_runs_) {
    bytes += static_cast<long>(column_runs_[static_cast<size_t>(c)].capacity() *
                               sizeof(std::pair<int, int>));
  }
  return bytes;
}

Occupancy OccupancyGrid::At(const Vec3& p) const {
  int ix, iy, iz;
  if (!CellOf(p, &ix, &iy, &iz)) return Occupancy::kUnknown;
  const size_t k = static_cast<size_t>(Index(ix, iy, iz));
  if (cells_[k].stamp == 0) return Occupancy::kUnknown;
  return cells_[k].log_odds > 0.0f ? Occupancy::kOccupied : Occupancy::kFree;
}

void OccupancyGrid::Update(long index, float change) {
  const size_t k = static_cast<size_t>(index);
  Cell& cell = cells_[k];
  if (cell.stamp == frame_) return;
  const bool observed = cell.stamp != 0;
  const bool was_occupied = observed && cell.log_odds > 0.0f;
  const bool was_free = observed && !was_occupied;
  cell.stamp = frame_;
  cell.log_odds = std::clamp(cell.log_odds + change, kLowest, kHighest);
  const bool occupied = cell.log_odds > 0.0f;
  occupied_ += static_cast<long>(occupied) - static_cast<long>(was_occupied);
  free_ += static_cast<long>(!occupied) - static_cast<long>(was_free);
  if (observed && occupied == was_occupied) return;
  const long column = index / nz_;
  if (!column_dirty_[static_cast<size_t>(column)]) {
    column_dirty_[static_cast<size_t>(column)] = 1;
    dirty_columns_.push_back(column);
  }
}

void OccupancyGrid::Clear(const Vec3& a, const Vec3& b, bool include_end) {
  // the part of a -> b inside the grid (slabs), then a 3-D DDA (Amanatides and Woo) over it
  const Vec3 d = b - a;
  double t0 = 0.0, t1 = 1.0;
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0.0) {
      if (a[i] < bounds_.min[i] || a[i] > bounds_.max[i]) return;
      continue;
    }
    double lo = (bounds_.min[i] - a[i]) / d[i], hi = (bounds_.max[i] - a[i]) / d[i];
    if (lo > hi) std::swap(lo, hi);
    t0 = std::max(t0, lo);
    t1 = std::min(t1, hi);
  }
  if (t0 > t1) return;
  int cell[3], end[3], step[3];
  CellOf(a + t0 * d, &cell[0], &cell[1], &cell[2]);
  CellOf(a + t1 * d, &end[0], &end[1], &end[2]);
  double next[3], delta[3];
  for (int i = 0; i < 3; ++i) {
    step[i] = d[i] > 0 ? 1 : (d[i] < 0 ? -1 : 0);
    const double edge = bounds_.min[i] + (cell[i] + (step[i] > 0 ? 1 : 0)) * resolution_;
    next[i] = step[i] != 0 ? (edge - a[i]) / d[i] : 2.0;
    delta[i] = step[i] != 0 ? resolution_ / std::abs(d[i]) : 2.0;
  }
  const bool ends_inside = t1 >= 1.0;
  const long stride[3] = {static_cast<long>(ny_) * nz_, nz_, 1};
  const int size[3] = {nx_, ny_, nz_};
  long index = Index(cell[0], cell[1], cell[2]);
  const long last = Index(end[0], end[1], end[2]);
  for (int guard = nx_ + ny_ + nz_ + 3; guard > 0; --guard) {
    const bool at_end = index == last;
    if (at_end && ends_inside && !include_end) return;
    if (cells_[static_cast<size_t>(index)].stamp != frame_) Update(index, kMiss);
    if (at_end) return;
    const int axis = next[0] < next[1] ? (next[0] < next[2] ? 0 : 2) : (next[1] < next[2] ? 1 : 2);
    if (next[axis] > t1) return;
    cell[axis] += step[axis];
    if (cell[axis] < 0 || cell[axis] >= size[axis]) return;
    index += step[axis] * stride[axis];
    next[axis] += delta[axis];
  }
}

int OccupancyGrid::Insert(const DepthImage& image, double range, const std::vector<bool>& ignored) {
  ++frame_;
  const long before = occupied_;
  const auto is_obstacle = [&ignored](int hit) {
    return hit >= 0 &&
           !(static_cast<size_t>(hit) < ignored.size() && ignored[static_cast<size_t>(hit)]);
  };
  // each pixel's ray's end: a surface point a millimetre on into the surface (the cell behind a
  // face is the one it belongs to, whichever side the ray came from), or the range
  const size_t pixels = image.depth.size();
  ends_.resize(pixels);
  for (int v = 0; v < image.height; ++v) {
    for (int u = 0; u < image.width; ++u) {
      const size_t k = static_cast<size_t>(v * image.width + u);
      if (image.depth[k] > 0.0f) {
        const Vec3 p = image.PointW(u, v);
        ends_[k] = p + 1e-3 * (p - image.origin_W).normalized();
      } else {
        ends_[k] = image.origin_W + image.R_WC * image.RayC(u, v) * range;
      }
    }
  }
  // occupied first: a cell a ray ends in is not cleared by its neighbours' rays this frame
  for (size_t k = 0; k < pixels; ++k) {
    if (image.depth[k] <= 0.0f || !is_obstacle(image.hit[k])) continue;
    int ix, iy, iz;
    if (CellOf(ends_[k], &ix, &iy, &iz)) Update(Index(ix, iy, iz), kHit);
  }
  // then the free space before each ray's end: one ray per end cell (OctoMap's `discretize`),
  // the first pixel's, so that the many pixels on a near surface walk the same cells once; a ray
  // that hit nothing apart from one that hit something there, and a ray whose end lies beyond
  // the grid by more than a cell on its own (rays to it differ too much). Each cell changes once
  // a frame, and every walk only clears: the order of the walks does not matter.
  if (walked_.size() != cells_.size()) walked_.assign(cells_.size(), 0);
  const std::uint32_t stamp = frame_ << 2;  // the two low bits: a surface's ray, a ray to range
  for (size_t k = 0; k < pixels; ++k) {
    const bool surface = image.depth[k] > 0.0f;
    if (!surface && image.hit[k] != kNoReturn) continue;  // dropped: says nothing
    const Vec3& p = ends_[k];
    const bool near_grid = (p.array() >= bounds_.min.array() - resolution_).all() &&
                           (p.array() <= bounds_.max.array() + resolution_).all();
    if (near_grid) {
      int ix, iy, iz;
      CellOf(p, &ix, &iy, &iz);  // clamped to the grid
      std::uint32_t& mark = walked_[static_cast<size_t>(Index(ix, iy, iz))];
      const std::uint32_t kind = surface ? 1 : 2;
      if ((mark & ~3u) != stamp) mark = stamp;
      if (mark & kind) continue;
      mark |= kind;
    }
    Clear(image.origin_W, p, !surface);
  }
  return static_cast<int>(std::max(0L, occupied_ - before));
}

OccupancyGrid::Runs OccupancyGrid::ColumnRuns(long column, bool columns) const {
  const long base = column * nz_;
  const auto known = [this, base](int z) {
    return cells_[static_cast<size_t>(base + z)].stamp != 0;
  };
  const auto occupied = [this, base, &known](int z) {
    return known(z) && cells_[static_cast<size_t>(base + z)].log_odds > 0.0f;
  };
  // runs of occupied cells, grown through unknown cells with `columns`; overlapping grown runs
  // join
  Runs runs;
  for (int z = 0; z < nz_; ++z) {
    if (!occupied(z)) continue;
    int lo = z, hi = z;
    while (hi + 1 < nz_ && occupied(hi + 1)) ++hi;
    z = hi;
    if (columns) {
      while (lo > 0 && !known(lo - 1)) --lo;
      while (hi + 1 < nz_ && !known(hi + 1)) ++hi;
    }
    if (!runs.empty() && lo <= runs.back().second + 1) {
      runs.back().second = std::max(runs.back().second, hi);
    } else {
      runs.push_back({lo, hi});
    }
  }
  return runs;
}

std::vector<Aabb> OccupancyGrid::OccupiedBoxes(bool columns) const {
  // the z-runs of each column (kept, redone for the columns that changed) ...
  if (runs_grown_ != static_cast<int>(columns)) {
    runs_grown_ = static_cast<int>(columns);
    dirty_columns_.clear();
    for (long c = 0; c < static_cast<long>(column_runs_.size()); ++c) dirty_columns_.push_back(c);
  }
  for (const long c : dirty_columns_) {
    const size_t k = static_cast<size_t>(c);
    column_dirty_[k] = 0;
    column_runs_[k] = ColumnRuns(c, columns);
    if (column_runs_[k].empty()) {
      columns_with_runs_.erase(c);
    } else {
      columns_with_runs_.insert(c);
    }
  }
  dirty_columns_.clear();
  std::map<std::tuple<long, int, int>, std::vector<int>> runs;  // (ix, z0, z1) -> the iy's
  for (const long c : columns_with_runs_) {
    for (const auto& [z0, z1] : column_runs_[static_cast<size_t>(c)]) {
      runs[{c / ny_, z0, z1}].push_back(static_cast<int>(c % ny_));
    }
  }
  // ... then runs of the same z-run along y, and runs of the same rectangle along x
  std::map<std::tuple<int, int, int, int>, std::vector<long>> slabs;  // (y0, y1, z0, z1) -> ix's
  for (const auto& [key, ys] : runs) {
    const auto [ix, z0, z1] = key;
    for (size_t i = 0; i < ys.size();) {
      size_t j = i;
      while (j + 1 < ys.size() && ys[j + 1] == ys[j] + 1) ++j;
      slabs[{ys[i], ys[j], z0, z1}].push_back(ix);
      i = j + 1;
    }
  }
  std::vector<Aabb> boxes;
  for (const auto& [key, xs] : slabs) {
    const auto [y0, y1, z0, z1] = key;
    for (size_t i = 0; i < xs.size();) {
      size_t j = i;
      while (j + 1 < xs.size() && xs[j + 1] == xs[j] + 1) ++j;
      const Vec3 min = bounds_.min + resolution_ * Vec3(xs[i], y0, z0);
      const Vec3 max = bounds_.min + resolution_ * Vec3(xs[j] + 1, y1 + 1, z1 + 1);
      boxes.push_back({min, max.cwiseMin(bounds_.max)});
      i = j + 1;
    }
  }
  return boxes;
}

}  // namespace aerobox
