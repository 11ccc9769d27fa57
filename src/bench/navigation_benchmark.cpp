#include "bench/navigation_benchmark.h"

#include <algorithm>
#include <iomanip>

#include "map/forest.h"
#include "mission/mission.h"
#include "scenario/scenario.h"

namespace aerobox {
namespace {

// Precision: occupied cells that overlap a true box. Recall: of the cells that overlap a true
// box and that the camera observed, the share marked occupied (the insides of pillars are never
// observed, so they do not count).
struct MapQuality {
  long occupied = 0, true_occupied = 0;
  long observed_in_boxes = 0, occupied_in_boxes = 0;
};

MapQuality Quality(const OccupancyGrid& grid, const Map& map) {
  MapQuality q;
  const double r = grid.resolution();
  for (const Aabb& run : grid.OccupiedBoxes()) {
    for (double x = run.min.x() + 0.5 * r; x < run.max.x(); x += r) {
      for (double y = run.min.y() + 0.5 * r; y < run.max.y(); y += r) {
        for (double z = run.min.z() + 0.5 * r; z < run.max.z(); z += r) {
          const Aabb cell{Vec3(x, y, z).array() - 0.5 * r, Vec3(x, y, z).array() + 0.5 * r};
          ++q.occupied;
          q.true_occupied += FirstOverlappingBox(map, cell).has_value() ? 1 : 0;
        }
      }
    }
  }
  for (const Box& box : map.boxes) {
    const Aabb& b = box.extent;
    for (double x = r * std::floor(b.min.x() / r) + 0.5 * r; x < b.max.x(); x += r) {
      for (double y = r * std::floor(b.min.y() / r) + 0.5 * r; y < b.max.y(); y += r) {
        for (double z = r * std::floor(b.min.z() / r) + 0.5 * r; z < b.max.z(); z += r) {
          const Occupancy o = grid.At(Vec3(x, y, z));
          if (o == Occupancy::kUnknown) continue;
          ++q.observed_in_boxes;
          q.occupied_in_boxes += o == Occupancy::kOccupied ? 1 : 0;
        }
      }
    }
  }
  return q;
}

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
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
  for (const int pillars : params.densities) {
    int reached = 0, contacts = 0, replans = 0;
    std::vector<double> speedups;
    double wall = 0, capture = 0, fusion = 0, rebuild = 0, planning = 0;
    MapQuality quality;
    std::string failures;
    for (int seed = 1; seed <= params.seeds; ++seed) {
      progress.Show("navigation: " + std::to_string(pillars) + " pillars, seed " +
                    std::to_string(seed));
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
      if (seed == 1) quality = Quality(*result.occupancy->grid, setup.map);
    }
    const auto share = [wall](double part) { return wall > 0 ? 100.0 * part / wall : 0.0; };
    out << std::fixed << std::setprecision(1) << "| " << pillars << " | " << reached << "/"
        << params.seeds << " | " << contacts << " | " << replans << " | " << Median(speedups)
        << " | " << share(capture) << " % | " << share(fusion) << " % | " << share(rebuild)
        << " % | " << share(planning) << " % | "
        << share(wall - capture - fusion - rebuild - planning) << " % | " << std::setprecision(3)
        << (quality.occupied ? double(quality.true_occupied) / quality.occupied : 0.0) << " | "
        << (quality.observed_in_boxes
                ? double(quality.occupied_in_boxes) / quality.observed_in_boxes
                : 0.0)
        << " | " << (failures.empty() ? "none" : failures) << " |\n"
        << std::defaultfloat << std::flush;
  }
  out << "\n(map precision and recall: the first seed's map at the end of its flight; recall "
         "counts the cells inside true boxes that the camera observed)\n";
  progress.Clear();
}

}  // namespace aerobox
