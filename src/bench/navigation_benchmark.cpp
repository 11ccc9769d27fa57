#include "bench/navigation_benchmark.h"

#include <algorithm>
#include <functional>
#include <iomanip>
#include <limits>

#include "bench/octomap_reference.h"
#include "common/wall_clock.h"
#include "map/forest.h"
#include "mission/mission.h"
#include "scenario/scenario.h"

namespace aerobox {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Precision: occupied cells that overlap a true box. Recall: of the cells that overlap a true
// box and that the camera observed, the share marked occupied (the insides of pillars are never
// observed, so they do not count). Only cells whose centres lie above `above` [m] count.
struct MapQuality {
  long occupied = 0, true_occupied = 0;
  long observed_in_boxes = 0, occupied_in_boxes = 0;
  double precision() const { return occupied ? double(true_occupied) / occupied : 0.0; }
  double recall() const {
    return observed_in_boxes ? double(occupied_in_boxes) / observed_in_boxes : 0.0;
  }
};

MapQuality Quality(const std::vector<Vec3>& occupied,
                   const std::function<Occupancy(const Vec3&)>& at, double r, const Map& map,
                   double above) {
  MapQuality q;
  for (const Vec3& c : occupied) {
    if (c.z() <= above) continue;
    ++q.occupied;
    const Aabb cell{c.array() - 0.5 * r, c.array() + 0.5 * r};
    q.true_occupied += FirstOverlappingBox(map, cell).has_value() ? 1 : 0;
  }
  for (const Box& box : map.boxes) {
    const Aabb& b = box.extent;
    for (double x = r * std::floor(b.min.x() / r) + 0.5 * r; x < b.max.x(); x += r) {
      for (double y = r * std::floor(b.min.y() / r) + 0.5 * r; y < b.max.y(); y += r) {
        for (double z = r * std::floor(b.min.z() / r) + 0.5 * r; z < b.max.z(); z += r) {
          if (z <= above) continue;
          const Occupancy o = at(Vec3(x, y, z));
          if (o == Occupancy::kUnknown) continue;
          ++q.observed_in_boxes;
          q.occupied_in_boxes += o == Occupancy::kOccupied ? 1 : 0;
        }
      }
    }
  }
  return q;
}

// The centres of a grid's occupied cells [m].
std::vector<Vec3> OccupiedCentres(const OccupancyGrid& grid) {
  std::vector<Vec3> centres;
  const double r = grid.resolution();
  for (const Aabb& run : grid.OccupiedBoxes()) {
    for (double x = run.min.x() + 0.5 * r; x < run.max.x(); x += r) {
      for (double y = run.min.y() + 0.5 * r; y < run.max.y(); y += r) {
        for (double z = run.min.z() + 0.5 * r; z < run.max.z(); z += r) {
          centres.push_back(Vec3(x, y, z));
        }
      }
    }
  }
  return centres;
}

MapQuality Quality(const OccupancyGrid& grid, const Map& map, double above) {
  return Quality(
      OccupiedCentres(grid), [&grid](const Vec3& p) { return grid.At(p); }, grid.resolution(), map,
      above);
}

// The flight's frames fused once more into a grid of ours and into OctoMap, each timed alone.
class FusionComparison : public MissionObserver {
 public:
  // `frames`: the flight's first so many frames (fewer than it takes: all of them)
  FusionComparison(const Aabb& bounds, const OccupancyParams& params, double range, int frames)
      : grid_(bounds, params), octomap_(params.resolution), range_(range), max_frames_(frames) {}

  void OnDepthFrame(double, const DepthImage& image, const OccupancyGrid&) override {
    if (frames_ >= max_frames_) return;
    auto begin = WallClock::now();
    grid_.Insert(image, range_, {});
    ours_ += Seconds(begin);
    begin = WallClock::now();
    octomap_.Insert(image, range_);
    theirs_ += Seconds(begin);
    ++frames_;
  }

  // One table row per map: fusion per frame, speed against OctoMap's, memory, quality.
  void Table(const Map& map, std::ostream& out) const {
    const double r = grid_.resolution(), above = map.bounds.min.z() + r;
    const MapQuality ours = Quality(grid_, map, above);
    const MapQuality theirs = Quality(
        octomap_.OccupiedCentres(map.bounds), [this](const Vec3& p) { return octomap_.At(p); }, r,
        map, above);
    const double n = std::max(1, frames_);
    out << "\nOccupancy maps, the same " << frames_
        << " depth frames (of the first seed's flight) fused into each: our voxel grid against "
           "OctoMap 1.9's octree (insertPointCloud with discretize: one ray per end cell, as "
           "ours). Quality above the floor's layer of cells (OctoMap maps the floor, ours knows "
           "it).\n\n| map | fusion per frame | speed | memory | precision | recall |\n"
           "|---|---|---|---|---|---|\n"
        << std::fixed << std::setprecision(2) << "| voxel grid (ours) | " << 1e3 * ours_ / n
        << " ms | " << (ours_ > 0 ? theirs_ / ours_ : 0.0) << "x | " << std::setprecision(1)
        << grid_.memory() / 1e6 << " MB | " << std::setprecision(3) << ours.precision() << " | "
        << ours.recall() << " |\n"
        << std::setprecision(2) << "| OctoMap | " << 1e3 * theirs_ / n << " ms | 1.00x | "
        << std::setprecision(1) << octomap_.memory() / 1e6 << " MB | " << std::setprecision(3)
        << theirs.precision() << " | " << theirs.recall() << " |\n"
        << std::defaultfloat;
  }

 private:
  OccupancyGrid grid_;
  OctoMapReference octomap_;
  double range_;
  int max_frames_;
  double ours_ = 0.0, theirs_ = 0.0;  // [s]
  int frames_ = 0;
};

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// A forest of `pillars` for `seed`, every pillar unknown, flown with `base`'s settings.
FlightSetup ForestSetup(const FlightSetup& base, const NavigationBenchParams& params, int pillars,
                        int seed) {
  ForestParams forest;
  forest.pillars = params.size.smoke ? pillars / 10 : pillars;
  forest.size = params.size.smoke ? Vec3(12, 8, 3) : forest.size;
  forest.seed = seed;
  FlightSetup setup = base;
  setup.map = MakeForest(forest);
  setup.start = *setup.map.start;
  setup.goal = *setup.map.goal;
  setup.seed = static_cast<std::uint64_t>(seed);
  setup.unknown.assign(setup.map.boxes.size(), true);
  setup.planning.trajectory.max_speed = params.max_speed;
  return setup;
}

// One row of the table: `pillars` over every seed.
void DensityRow(const FlightSetup& base, const NavigationBenchParams& params, int pillars,
                std::ostream& out, ProgressDisplay& progress) {
  int reached = 0, contacts = 0, replans = 0;
  std::vector<double> speedups;
  double wall = 0, capture = 0, fusion = 0, rebuild = 0, planning = 0;
  MapQuality quality;
  std::string failures;
  for (int seed = 1; seed <= params.seeds; ++seed) {
    progress.Show("navigation: " + std::to_string(pillars) + " pillars, seed " +
                  std::to_string(seed));
    const FlightSetup setup = ForestSetup(base, params, pillars, seed);
    const MissionResult result = RunMission(setup, MissionParts());
    if (result.status == MissionStatus::kReachedGoal) {
      ++reached;
    } else {
      failures += (failures.empty() ? "" : ", ") + std::to_string(seed) + ": " + Outcome(result);
    }
    contacts += result.flown && result.flight.status == FlightStatus::kCollision ? 1 : 0;
    replans += static_cast<int>(result.replans.size());
    if (!result.flown || !result.occupancy) continue;
    speedups.push_back(result.flight.time / result.flight_wall_time);
    wall += result.flight_wall_time;
    capture += result.occupancy->cost.capture;
    fusion += result.occupancy->cost.fusion;
    rebuild += result.occupancy->cost.rebuild;
    for (const ReplanEvent& e : result.replans) planning += e.latency;
    if (seed == 1) quality = Quality(*result.occupancy->grid, setup.map, -kInf);
  }
  const auto share = [wall](double part) { return wall > 0 ? 100.0 * part / wall : 0.0; };
  out << std::fixed << std::setprecision(1) << "| " << pillars << " | " << reached << "/"
      << params.seeds << " | " << contacts << " | " << replans << " | " << Median(speedups) << " | "
      << share(capture) << " % | " << share(fusion) << " % | " << share(rebuild) << " % | "
      << share(planning) << " % | " << share(wall - capture - fusion - rebuild - planning)
      << " % | " << std::setprecision(3) << quality.precision() << " | " << quality.recall()
      << " | " << (failures.empty() ? "none" : failures) << " |\n"
      << std::defaultfloat << std::flush;
}

}  // namespace

void NavigationTable(const NavigationBenchParams& params, std::ostream& out,
                     ProgressDisplay& progress) {
  const FlightSetup base = LoadFlightSetup(params.scenario, {});
  const DepthCameraParams camera = base.sensing.Camera();
  out << "Depth camera " << camera.width << " x " << camera.height << " px at " << base.sensing.rate
      << " Hz, " << camera.range << " m; occupancy map " << base.sensing.map.resolution
      << " m; trajectories at most " << params.max_speed
      << " m/s; the forest's pillars all unknown. Faster than real time: flight time over wall "
         "time (median); the shares are of the flight's wall time.\n\n"
      << "| pillars | reached | contacts | replans | x real time | ray cast | fusion | "
         "planner's world | replanning | rest (physics, control) | map precision | map recall "
         "| failures (seed: why) |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const int pillars : params.densities) DensityRow(base, params, pillars, out, progress);
  out << "\n(map precision and recall: the first seed's map at the end of its flight; recall "
         "counts the cells inside true boxes that the camera observed)\n";
  if (!params.densities.empty()) {
    progress.Show("navigation: our occupancy map against OctoMap's");
    const FlightSetup setup = ForestSetup(base, params, params.densities.front(), 1);
    FusionComparison comparison(setup.map.bounds, base.sensing.map, base.sensing.range,
                                params.size.smoke ? 50 : std::numeric_limits<int>::max());
    MissionParts parts;
    parts.observers.push_back(&comparison);
    RunMission(setup, parts);
    comparison.Table(setup.map, out);
  }
  progress.Clear();
}

}  // namespace aerobox
