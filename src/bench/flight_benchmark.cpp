#include "bench/flight_benchmark.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <functional>
#include <iomanip>
#include <map>
#include <memory>
#include <vector>

#include "bench/benchmark_medians.h"
#include "mission/flight.h"
#include "mission/plan.h"
#include "mission/telemetry_table.h"
#include "scenario/scenario.h"

namespace aerobox {
namespace {

constexpr double kWindow = 2.0;  // [s] of flight per benchmark iteration

// The controls MuJoCo saw at each step of a recorded flight (mjcb_control is global; the
// benchmark is single-threaded and clears it after recording).
std::vector<std::vector<double>>* recorded_controls = nullptr;

void RecordControls(const mjModel* m, mjData* d) {
  recorded_controls->emplace_back(d->ctrl, d->ctrl + m->nu);
}

}  // namespace

void CompareClosedLoop(const std::string& scenario, std::ostream& out, ProgressDisplay& progress,
                       const BenchSize& size) {
  const FlightSetup setup = LoadFlightSetup(scenario, {});
  const PlanOutcome plan = PlanFlight(setup);
  if (!plan.trajectory || plan.trajectory->status != TrajectoryStatus::kSolved) {
    out << "(no trajectory on " << scenario << ": nothing to fly)\n";
    return;
  }
  const std::string xml = SceneMjcfFor(setup);
  const QuadParams& vehicle = setup.vehicle;
  const Reference full = ReferenceOf(plan.trajectory->trajectory);
  const CollisionWorld world(setup.map, CollisionParams{vehicle.collision_size, 0.0});
  // telemetry.csv's columns for the controller that flies (the cascade reports its own)
  const TelemetrySchema schema(*MakeController(setup.controller, vehicle), TelemetryExtras());

  // the trajectory in 2 s windows, each flown from its own start state
  const int windows = size.Count(std::max(1, static_cast<int>(full.duration / kWindow)), 1);
  const auto window_reference = [&full](int w) {
    const double t0 = kWindow * w;
    Reference slice;
    slice.duration = kWindow - 1e-9;
    slice.evaluate = [&full, t0](double t, int d) {
      return full.evaluate(std::min(t0 + t, full.duration), d);
    };
    return slice;
  };
  const auto start_window = [&](int w) {
    auto sim = std::make_unique<Simulation>(Simulation::FromXml(xml, "bench"));
    const Reference slice = window_reference(w);
    sim->SetVehicleState(State{slice.evaluate(0, kPosition), slice.evaluate(0, kVelocity),
                               Quat::Identity(), Vec3::Zero()});
    sim->SetRotorThrusts(Vec4::Constant(vehicle.HoverThrustPerRotor()));
    return sim;
  };
  const auto fly_window = [&](int w, bool with_clearance, bool with_telemetry, Simulation* sim,
                              CsvTable* telemetry) {
    FlightParams params;
    params.settle_time = 0.0;
    std::function<double(const Vec3&)> clearance;
    if (with_clearance) clearance = [&world](const Vec3& p) { return world.Clearance(p); };
    std::function<void(const TelemetrySample&)> sink;
    if (with_telemetry) {
      sink = [&schema, telemetry](const TelemetrySample& s) { schema.AddRow(s, telemetry); };
    }
    return FlyTrajectory(window_reference(w), params, vehicle, setup.controller, clearance, sink,
                         sim);
  };

  // bare: each window's recorded controls replayed open loop with mj_step alone, so MuJoCo
  // does the same work (same states, same contact candidates near the walls) as in the flight
  std::vector<std::vector<std::vector<double>>> controls(windows);
  for (int w = 0; w < windows; ++w) {
    const std::unique_ptr<Simulation> sim = start_window(w);
    CsvTable telemetry = schema.Table();
    recorded_controls = &controls[w];
    mjcb_control = RecordControls;
    fly_window(w, true, true, sim.get(), &telemetry);
    mjcb_control = nullptr;
    recorded_controls = nullptr;
  }
  long steps_per_pass = 0;
  for (const auto& c : controls) steps_per_pass += static_cast<long>(c.size());

  // each iteration flies (or replays) every window once
  const auto register_loop = [&](const char* name, auto run_window) {
    Sized(benchmark::RegisterBenchmark(name,
                                       [&, run_window](benchmark::State& state) {
                                         for (auto _ : state) {
                                           for (int w = 0; w < windows; ++w) {
                                             state.PauseTiming();
                                             std::unique_ptr<Simulation> sim = start_window(w);
                                             CsvTable telemetry = schema.Table();
                                             state.ResumeTiming();
                                             run_window(w, sim.get(), &telemetry);
                                             benchmark::DoNotOptimize(telemetry.rows());
                                           }
                                         }
                                       })
              ->Unit(benchmark::kSecond),
          size, 5);
  };
  register_loop("bare", [&](int w, Simulation* sim, CsvTable*) {
    const mjModel* m = sim->model();
    mjData* d = sim->mutable_data();
    for (const std::vector<double>& ctrl : controls[w]) {
      std::copy(ctrl.begin(), ctrl.end(), d->ctrl);
      mj_step(m, d);
    }
  });
  register_loop("cascade", [&](int w, Simulation* sim, CsvTable* telemetry) {
    fly_window(w, false, false, sim, telemetry);
  });
  register_loop("closed", [&](int w, Simulation* sim, CsvTable* telemetry) {
    fly_window(w, true, true, sim, telemetry);
  });

  progress.Show("timing the closed loop ...", true);
  const std::map<std::string, double> medians = RunRegisteredBenchmarks();
  progress.Clear();

  const double bare = steps_per_pass / medians.at("bare");
  const double cascade = steps_per_pass / medians.at("cascade");
  const double closed = steps_per_pass / medians.at("closed");
  out << std::fixed << std::setprecision(0) << "| loop | steps/s |\n|---|---|\n"
      << "| bare mj_step, the flight's controls replayed | " << bare << " |\n"
      << "| cascade and contact check | " << cascade << " |\n"
      << "| closed loop (cascade, contacts, clearance, telemetry) | " << closed << " |\n\n"
      << std::setprecision(2) << "Ratio closed / bare: " << closed / bare << "\n";
}

}  // namespace aerobox
