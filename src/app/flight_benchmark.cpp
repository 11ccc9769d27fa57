#include "app/flight_benchmark.h"

#include <benchmark/benchmark.h>

#include <iomanip>
#include <map>

#include "app/benchmark_medians.h"
#include "app/flight.h"
#include "app/fly_job.h"
#include "app/plan_job.h"

namespace aerobox {
namespace {

constexpr int kStepsPerIteration = 2000;  // 2 s of flight at 1 ms

}  // namespace

void CompareClosedLoop(const std::string& scenario, std::ostream& out, std::ostream& progress) {
  const FlightSetup setup = LoadFlightSetup(scenario, {});
  const PlanOutcome plan = PlanFlight(setup);
  if (!plan.trajectory || plan.trajectory->status != TrajectoryStatus::kSolved) {
    out << "(no trajectory on " << scenario << ": nothing to fly)\n";
    return;
  }
  const std::string xml = SceneMjcfFor(setup);
  const QuadParams vehicle;
  const Reference full = ReferenceOf(plan.trajectory->trajectory);

  // bare: the same model, mj_step with hover thrusts, nothing else
  benchmark::RegisterBenchmark("bare",
                               [&](benchmark::State& state) {
                                 Simulation sim = Simulation::FromXml(xml, "bench");
                                 sim.SetRotorThrusts(Vec4::Constant(vehicle.HoverThrustPerRotor()));
                                 const Vec4 hover = Vec4::Constant(vehicle.HoverThrustPerRotor());
                                 for (auto _ : state) {
                                   for (int i = 0; i < kStepsPerIteration; ++i) sim.Step(hover);
                                 }
                               })
      ->Unit(benchmark::kSecond)
      ->Repetitions(5)
      ->ReportAggregatesOnly(true);

  // closed loop: 2 s windows of the scenario's trajectory, with the cascade, the contact
  // check, the clearance query and a telemetry row every control step
  const CollisionWorld world(setup.map, CollisionParams{vehicle.collision_size, 0.0});
  benchmark::RegisterBenchmark(
      "closed",
      [&](benchmark::State& state) {
        FlightParams params;
        params.settle_time = 0.0;
        long window = 0;
        for (auto _ : state) {
          state.PauseTiming();
          Simulation sim = Simulation::FromXml(xml, "bench");
          const double t0 = 2.0 * (window++ % std::max(1, static_cast<int>(full.duration / 2.0)));
          const Reference slice{2.0 - 1e-9, [&full, t0](double t, int d) {
                                  return full.evaluate(std::min(t0 + t, full.duration), d);
                                }};
          sim.SetVehicleState(State{slice.evaluate(0, kPosition), slice.evaluate(0, kVelocity),
                                    Quat::Identity(), Vec3::Zero()});
          sim.SetRotorThrusts(Vec4::Constant(vehicle.HoverThrustPerRotor()));
          CsvTable telemetry = TelemetryTable();
          state.ResumeTiming();
          const FlightResult result = FlyTrajectory(
              slice, params, vehicle, [&world](const Vec3& p) { return world.Clearance(p); },
              [&telemetry](const TelemetrySample& s) { AddTelemetryRow(s, &telemetry); }, &sim);
          state.counters["steps"] = static_cast<double>(result.steps);
          benchmark::DoNotOptimize(telemetry.rows());
        }
      })
      ->Unit(benchmark::kSecond)
      ->Repetitions(5)
      ->ReportAggregatesOnly(true);

  progress << "timing the closed loop ..." << std::flush;
  const std::map<std::string, double> medians = RunRegisteredBenchmarks();
  progress << "\r" << std::string(40, ' ') << "\r" << std::flush;

  const double bare = kStepsPerIteration / medians.at("bare");
  const double closed = kStepsPerIteration / medians.at("closed");
  out << std::fixed << std::setprecision(0) << "| loop | steps/s |\n|---|---|\n"
      << "| bare mj_step | " << bare << " |\n| closed loop (cascade, contacts, clearance, "
      << "telemetry) | " << closed << " |\n\n"
      << std::setprecision(2) << "Ratio closed / bare: " << closed / bare << "\n";
}

}  // namespace aerobox
