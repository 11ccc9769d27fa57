#include "bench/city_benchmark.h"

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <random>
#include <vector>

#include "common/wall_clock.h"
#include "mission/plan.h"
#include "planning/lattice_planner.h"
#include "planning/path_simplify.h"
#include "scenario/scenario.h"
#include "scene/scene_mjcf.h"
#include "sim/simulation.h"

namespace aerobox {
namespace {

constexpr double kRouteMargin = 25.0;  // [m] as `aerobox fly` keeps in a city's scene
constexpr int kSteps = 1000;           // per timing of MuJoCo's step
constexpr int kRepetitions = 5;

// Median over `repetitions` of mj_step's rate [steps/s] with the vehicle hovering at `at`.
double StepsPerSecond(const std::string& xml, const Vec3& at, int repetitions) {
  Simulation sim = Simulation::FromXml(xml, "bench");
  const QuadParams vehicle;
  const Vec4 hover = Vec4::Constant(vehicle.HoverThrustPerRotor());
  std::vector<double> rates;
  for (int r = 0; r < repetitions; ++r) {
    sim.SetVehicleState(State{at, Vec3::Zero(), Quat::Identity(), Vec3::Zero()});
    sim.SetRotorThrusts(hover);
    const auto begin = std::chrono::steady_clock::now();
    for (int i = 0; i < kSteps; ++i) sim.Step(hover);
    rates.push_back(kSteps / Seconds(begin));
  }
  std::nth_element(rates.begin(), rates.begin() + repetitions / 2, rates.end());
  return rates[repetitions / 2];
}

}  // namespace

void CityBenchmark(const std::string& city, const std::string& window, int queries,
                   std::ostream& out, ProgressDisplay& progress, const BenchSize& size) {
  const int repetitions = size.Repetitions(kRepetitions);
  FlightSetup setup = LoadFlightSetup(city, {});
  setup.planning.trajectory.max_speed = 8.0;  // a Tello's top speed
  setup.planning.trajectory.max_accel = 4.0;
  const CollisionWorld world(setup.map, setup.PlannerCollision());
  const Validity validity{
      [&world](const Vec3& p) { return world.IsPointFree(p); },
      [&world](const Vec3& a, const Vec3& b) { return world.IsSegmentFree(a, b); }};
  progress.Show("building the city lattice ...", true);
  const LatticePlanner planner(world.free_bounds(), validity, LatticeParamsFor(setup));

  // seeded random free pairs 600-700 m apart (in the plane), 10-60 m above the floor
  std::mt19937_64 rng(2026);
  const Aabb& b = setup.map.bounds;
  std::uniform_real_distribution<double> x(b.min.x() + 5, b.max.x() - 5);
  std::uniform_real_distribution<double> y(b.min.y() + 5, b.max.y() - 5);
  std::uniform_real_distribution<double> z(b.min.z() + 10, b.min.z() + 60);
  int solved = 0, rechecked = 0;
  double total = 0.0, slowest = 0.0;
  std::vector<Vec3> longest;
  for (int q = 0; q < queries;) {
    const Vec3 a(x(rng), y(rng), z(rng));
    const Vec3 g(x(rng), y(rng), z(rng));
    const double d = (a - g).head<2>().norm();
    if (d < 600 || d > 700 || !world.IsPointFree(a) || !world.IsPointFree(g)) continue;
    ++q;
    progress.Show("city queries " + std::to_string(q) + " / " + std::to_string(queries));
    const PlanResult result = planner.Plan(a, g);
    total += result.stats.planning_time;
    slowest = std::max(slowest, result.stats.planning_time);
    if (result.status != PlanStatus::kSolved) continue;
    ++solved;
    bool free = true;  // the exact segment test once more, apart from the planner
    for (size_t i = 1; i < result.path.size(); ++i)
      free = free && world.IsSegmentFree(result.path[i - 1], result.path[i]);
    rechecked += free;
    if (PathLength(result.path) > PathLength(longest)) longest = result.path;
  }
  progress.Show("the trajectory along the longest path ...", true);
  const TrajectoryResult trajectory = TrajectoryAlong(setup, longest);

  // MuJoCo: the window scene, the whole city, and the city as a flight along the longest path
  // keeps it (the buildings within 25 m of the trajectory)
  progress.Show("timing MuJoCo's steps ...", true);
  const FlightSetup window_setup = LoadFlightSetup(window, {});
  const double window_rate =
      StepsPerSecond(SceneMjcfFor(window_setup), window_setup.start, repetitions);
  const double city_rate = StepsPerSecond(SceneMjcfFor(setup), longest.front(), repetitions);
  std::vector<Vec3> route;
  for (double t = 0; t <= trajectory.trajectory.duration(); t += 0.1)
    route.push_back(trajectory.trajectory.Evaluate3(t, kPosition));
  const std::vector<bool> keep = RouteBoxes(setup.map, route, kRouteMargin);
  const long kept = std::count(keep.begin(), keep.end(), true);
  const double route_rate = StepsPerSecond(SceneMjcfFor(setup, keep), longest.front(), repetitions);
  progress.Clear();

  const LatticeStats& lattice = planner.stats();
  out << std::fixed << std::setprecision(3) << "Lattice: " << lattice.nodes << " nodes, "
      << lattice.edges << " edges, built once in " << lattice.build_time << " s.\n\n"
      << "| queries | solved | exact re-check passed | mean query [ms] | max query [ms] |\n"
      << "|---|---|---|---|---|\n"
      << "| " << queries << " | " << solved << " | " << rechecked << " | " << std::setprecision(2)
      << 1e3 * total / queries << " | " << 1e3 * slowest << " |\n\n"
      << "Longest path: " << std::setprecision(1) << PathLength(longest) << " m, "
      << longest.size() - 1
      << " segments; trajectory at up to 8 m/s: " << trajectory.trajectory.segments().size()
      << " segments, " << trajectory.trajectory.duration() << " s, solved in "
      << std::setprecision(3) << trajectory.stats.solve_time << " s ("
      << trajectory.stats.solver_message << ").\n\n"
      << "| MuJoCo scene | geoms | steps/s | against the window scene |\n|---|---|---|---|\n"
      << std::setprecision(0) << "| window | " << window_setup.map.boxes.size() << " boxes | "
      << window_rate << " | 1.00 |\n"
      << "| city, all buildings | " << setup.map.boxes.size() << " boxes | " << city_rate << " | "
      << std::setprecision(3) << city_rate / window_rate << " |\n"
      << std::setprecision(0) << "| city, as flown (buildings within 25 m of the route) | " << kept
      << " boxes | " << route_rate << " | " << std::setprecision(3) << route_rate / window_rate
      << " |\n";
}

}  // namespace aerobox
