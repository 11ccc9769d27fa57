#include "bench/rl_benchmark.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <optional>
#include <thread>
#include <vector>

#include "common/stop.h"
#include "common/worker_pool.h"
#include "envs/env_batch.h"

namespace aerobox {
namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point begin) {
  return std::chrono::duration<double>(Clock::now() - begin).count();
}

// [s] for `steps` environment steps of `n` worlds (zero actions: a hover thrust and no rates;
// episodes end and reset as they do in training).
double TimeEnvironment(const EnvParams& params, int n, int threads, long steps) {
  EnvBatch batch(params, n, threads);
  const int d = batch.observation_size(), k = params.ActionSize();
  std::vector<float> obs(static_cast<size_t>(n * d));
  std::vector<double> actions(static_cast<size_t>(n * k), 0.0), rewards(n),
      terms(static_cast<size_t>(n * batch.term_count()));
  std::vector<std::uint8_t> terminated(n), truncated(n);
  std::vector<std::optional<std::uint64_t>> seeds;
  for (int i = 0; i < n; ++i) seeds.emplace_back(i);
  batch.Reset(seeds, obs.data());
  const auto begin = Clock::now();
  for (long s = 0; s < steps; ++s) {
    ThrowIfStopRequested("timing the learning environments");
    batch.Step(actions.data(), obs.data(), rewards.data(), terminated.data(), truncated.data(),
               terms.data());
  }
  return Seconds(begin);
}

// [s] for the bare physics of the same: `n` copies of the scene, mj_step alone with the rotors
// at hover thrust from an episode's start, `physics` steps each, in the same threads.
double TimeBarePhysics(const EnvParams& params, int n, int threads, long physics) {
  const Map map = FindEnvTask(params.task).map(params);
  const Simulation scene = Simulation::FromXml(EnvSceneXml(params, map), "env");
  std::vector<Simulation> sims;
  for (int i = 0; i < n; ++i) sims.push_back(scene.Clone());
  const Vec4 hover = Vec4::Constant(params.Vehicle().HoverThrustPerRotor());
  // where an episode starts (Navigate's target is not free in its forest), level and at rest
  EnvBatch probe(params, 1, 1);
  std::vector<float> obs(static_cast<size_t>(probe.observation_size()));
  probe.Reset({0}, obs.data());
  State s;
  s.p_W = probe.world(0).state().p_W;
  for (Simulation& sim : sims) {
    sim.SetVehicleState(s);
    sim.SetRotorThrusts(hover);
  }
  WorkerPool pool(std::min(threads, n));
  const auto begin = Clock::now();
  pool.For(n, [&](int from, int to) {
    for (int i = from; i < to; ++i) {
      for (long s = 0; s < physics; ++s) sims[static_cast<size_t>(i)].Step(hover);
    }
  });
  return Seconds(begin);
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// One table row: `n` worlds of `params`, the environment against the bare physics.
void Row(std::ostream& out, const std::string& label, const EnvParams& params, int n, int threads,
         const BenchSize& size) {
  const long physics_per_step = std::lround(1000.0 / params.control_rate);
  const long steps = size.smoke ? 5 : std::max(100L, 40000L / n);
  std::vector<double> env, bare;
  for (int r = 0; r < size.Repetitions(3); ++r) {
    env.push_back(TimeEnvironment(params, n, threads, steps));
    bare.push_back(TimeBarePhysics(params, n, threads, steps * physics_per_step));
  }
  const double e = Median(env), b = Median(bare);
  const double rate = static_cast<double>(n) * steps / e;
  out << std::fixed << "| " << label << " | " << std::setprecision(0) << rate << " | "
      << rate / params.control_rate << " | " << static_cast<double>(n) * steps / b << " | "
      << std::setprecision(2) << e / b << " |\n"
      << std::defaultfloat << std::flush;
}

}  // namespace

void RunRlBenchmark(std::ostream& out, const BenchSize& size) {
  const EnvParams params;  // Hover-v0's defaults: the Crazyflie, 100 Hz, thrust and rates
  const int threads = std::max(1U, std::thread::hardware_concurrency());
  const char* header =
      " | env steps/s | simulated s per wall s | bare physics: env steps/s | env / bare time "
      "|\n|---|---|---|---|---|\n";
  out << "aerobox/Hover-v0 at " << params.control_rate << " Hz ("
      << std::lround(1000.0 / params.control_rate)
      << " MuJoCo steps of 1 ms per environment step), " << threads
      << " threads; the bare physics: the same worlds' mj_step alone, in the same threads. "
      << "Medians of " << size.Repetitions(3) << ".\n\n| worlds" << header;
  const std::vector<int> sizes =
      size.smoke ? std::vector<int>{1, 4} : std::vector<int>{1, 16, 64, 256};
  for (const int n : sizes) Row(out, std::to_string(n), params, n, threads, size);
  // each task, in its own scene (Navigate's forest: 30 trunks, 18 range rays per step)
  const int n = size.smoke ? 4 : 64;
  out << "\nEach task with " << n << " worlds (Navigate: a velocity action, 30 trees, "
      << params.range_rays + 2 << " range rays; its bare physics has the trees too).\n\n| task"
      << header;
  for (const char* task : {"hover", "track", "navigate"}) {
    EnvParams p;
    p.task = task;
    if (p.task == "navigate") p.action = "velocity";
    Row(out, task, p, n, threads, size);
  }
}

}  // namespace aerobox
