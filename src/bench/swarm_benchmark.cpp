#include "bench/swarm_benchmark.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <memory>
#include <vector>

#include "mission/reference_curves.h"
#include "mission/swarm_mission.h"
#include "scenario/scenario.h"
#include "scene/scene_mjcf.h"
#include "vehicle/quad_params.h"

namespace aerobox {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kRate = 500.0;  // [Hz] every vehicle's controller

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// [s] of wall time for `seconds` of flight of `n` Crazyflies, each circling 0.5 m around its own
// point of a 1.5 m grid with its own cascade at 500 Hz, in one world.
double FlightWallTime(int n, double seconds) {
  const QuadParams cf = *BuiltinVehicle("crazyflie");
  const int columns = static_cast<int>(std::ceil(std::sqrt(n)));
  std::vector<SceneVehicle> scene;
  std::vector<std::string> names;
  std::vector<Vec3> centres;
  for (int i = 0; i < n; ++i) {
    centres.push_back(Vec3(1.5 * (i % columns) - 4, 1.5 * (i / columns) - 4, 1.0));
    names.push_back("cf" + std::to_string(i + 1));
    scene.push_back({names.back(), cf, centres.back() + Vec3(0.5, 0, 0), SwarmRgba(i)});
  }
  Map room;
  room.name = "room";
  room.bounds = {Vec3(-6, -6, 0), Vec3(6, 6, 3)};
  Simulation sim = Simulation::FromXml(BuildSceneMjcf(room, scene, SceneOptions()), "room", names);
  ControllerConfig control;
  control.rate = kRate;
  std::vector<std::unique_ptr<Controller>> controllers;
  std::vector<SwarmVehicle> vehicles;
  for (int i = 0; i < n; ++i) {
    sim.vehicle(i).SetRotorThrusts(Vec4::Constant(cf.HoverThrustPerRotor()));
    controllers.push_back(MakeController(control, cf));
    SwarmVehicle v;
    v.name = names[i];
    const Vec3 c = centres[i];
    v.reference = FromFunction(seconds, [c](double t) {
      const double phase = RampedPhase(t, 1.0, 1.0, 1e9);
      return Vec3(c + 0.5 * Vec3(std::cos(phase), std::sin(phase), 0));
    });
    v.loop.vehicle = &cf;
    v.loop.controller = controllers.back().get();
    v.loop.control_rate = kRate;
    v.loop.inner = control.inner;
    v.loop.completion.kind = Completion::Kind::kNever;
    vehicles.push_back(std::move(v));
  }
  FlightParams params;
  params.settle_time = 0.0;
  const auto start = Clock::now();
  FlySwarm(vehicles, params, SwarmParams(), &sim);
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void CostTable(std::ostream& out, const BenchSize& size) {
  const double seconds = size.smoke ? 0.2 : 10.0;
  const int repetitions = size.Repetitions(3);
  out << "Crazyflies in one world, each circling with its own cascade at " << kRate
      << " Hz, one thread, " << seconds << " s of flight, medians of " << repetitions
      << "; per vehicle: wall time per vehicle against one vehicle alone, in the same run.\n\n"
      << "| vehicles | wall time [s] | x real time | per vehicle [ms per flight s] | per vehicle "
         "/ alone |\n|---|---|---|---|---|\n";
  double alone = 0.0;
  for (const int n : size.smoke ? std::vector<int>{1, 2} : std::vector<int>{1, 2, 5, 10, 20}) {
    std::vector<double> walls;
    for (int r = 0; r < repetitions; ++r) walls.push_back(FlightWallTime(n, seconds));
    const double wall = Median(walls);
    const double per_vehicle = wall / n;
    if (n == 1) alone = per_vehicle;
    out << std::fixed << "| " << n << " | " << std::setprecision(3) << wall << " | "
        << std::setprecision(1) << seconds / wall << " | " << std::setprecision(2)
        << 1e3 * per_vehicle / seconds << " | " << per_vehicle / alone << " |\n"
        << std::defaultfloat << std::flush;
  }
}

// The swap scenario with `n` vehicles evenly on its circle, each bound for the point opposite.
FlightSetup SwapOf(const FlightSetup& scene, int n) {
  FlightSetup setup = scene;
  const SwarmMember model = scene.vehicles.front();
  const double radius = model.start.head<2>().norm();
  setup.vehicles.clear();
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    SwarmMember m = model;
    m.name = "cf" + std::to_string(i + 1);
    m.start = Vec3(radius * std::cos(a), radius * std::sin(a), model.start.z());
    m.goal = Vec3(-m.start.x(), -m.start.y(), m.start.z());
    setup.vehicles.push_back(m);
  }
  return setup;
}

void SwapTable(const std::string& scenario, std::ostream& out, const BenchSize& size) {
  const FlightSetup scene = LoadFlightSetup(scenario, {});
  const double r = VehicleRadius(scene.vehicles.front().vehicle);
  out << "\nThe antipodal swap (scenes/swarm_swap): vehicles evenly on a circle of "
      << scene.vehicles.front().start.head<2>().norm()
      << " m radius, each bound for the point opposite, prioritised planning with "
      << scene.swarm.separation << " m kept beyond both radii (twice a radius: " << std::fixed
      << std::setprecision(3) << 2 * r << std::defaultfloat
      << " m). Makespan: the last arrival, planned (waits included) and flown (until within "
         "the goal's tolerance), against the longest trajectory flown alone.\n\n"
      << "| vehicles | arrived | contacts | min separation [m] | waited | bent | makespan "
         "planned [s] | flown [s] | alone [s] | planned / alone | planning wall [s] | flight "
         "wall [s] |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const int n : size.smoke ? std::vector<int>{4} : std::vector<int>{4, 8, 16}) {
    const auto start = Clock::now();
    const SwarmMissionResult result = RunSwarm(SwapOf(scene, n), SwarmParts());
    const double wall = std::chrono::duration<double>(Clock::now() - start).count();
    int arrived = 0, contacts = 0, waited = 0, bent = 0;
    double flown = 0.0;
    for (size_t i = 0; i < result.flight.flights.size(); ++i) {
      const FlightResult& f = result.flight.flights[i];
      arrived += result.schedule[i].flies && f.status == FlightStatus::kReachedGoal;
      contacts += f.status == FlightStatus::kCollision;
      waited += result.schedule[i].delay > 0;
      bent += !result.schedule[i].detour.empty();
      flown = std::max(flown, f.time);
    }
    out << std::fixed << std::setprecision(3) << "| " << n << " | " << arrived << "/" << n << " | "
        << contacts << " | " << result.flight.min_separation << " | " << waited << " | " << bent
        << " | " << result.makespan << " | " << flown << " | " << result.alone_makespan << " | "
        << std::setprecision(2) << result.makespan / result.alone_makespan << " | "
        << wall - result.flight_wall_time << " | " << result.flight_wall_time << " |\n"
        << std::defaultfloat << std::flush;
  }
}

}  // namespace

void RunSwarmBenchmark(const std::string& swap_scenario, std::ostream& out, const BenchSize& size) {
  CostTable(out, size);
  SwapTable(swap_scenario, out, size);
}

}  // namespace aerobox
