#include "bench/rl_benchmark.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <optional>
#include <stdexcept>
#include <thread>
#include <vector>

#include "common/stop.h"
#include "common/wall_clock.h"
#include "common/worker_pool.h"
#include "envs/env_batch.h"

namespace aerobox {
namespace {

using Clock = std::chrono::steady_clock;

// The MuJoCo state of one world at the start of one environment step: what the bare physics
// starts that step from.
struct PhysicsState {
  std::array<double, 7> qpos;
  std::array<double, 6> qvel;
  std::array<double, 4> act, ctrl;
  bool reset;  // the environment step reset the world instead (no physics)
};

PhysicsState StateOf(const Simulation& sim, bool reset) {
  const mjData* d = sim.data();
  PhysicsState s;
  std::copy(d->qpos, d->qpos + 7, s.qpos.begin());
  std::copy(d->qvel, d->qvel + 6, s.qvel.begin());
  std::copy(d->act, d->act + 4, s.act.begin());
  std::copy(d->ctrl, d->ctrl + 4, s.ctrl.begin());
  s.reset = reset;
  return s;
}

// [s] for `steps` environment steps of `n` worlds (zero actions: thrust mid-range, no rates;
// episodes end and reset as they do in training). Records each world's state at the start of
// each step in `states` (steps x n).
double TimeEnvironment(const EnvParams& params, int n, int threads, long steps,
                       std::vector<PhysicsState>* states) {
  EnvBatch batch(params, n, threads);
  const int d = batch.observation_size(), k = params.ActionSize();
  std::vector<float> obs(static_cast<size_t>(n * d));
  std::vector<double> actions(static_cast<size_t>(n * k), 0.0), rewards(n),
      terms(static_cast<size_t>(n * batch.term_count()));
  std::vector<std::uint8_t> terminated(n), truncated(n);
  std::vector<std::optional<std::uint64_t>> seeds;
  for (int i = 0; i < n; ++i) seeds.emplace_back(i);
  batch.Reset(seeds, obs.data());
  states->clear();
  double seconds = 0.0;
  for (long s = 0; s < steps; ++s) {
    ThrowIfStopRequested("timing the learning environments");
    for (int i = 0; i < n; ++i) {
      states->push_back(StateOf(batch.Showing(i), terminated[i] || truncated[i]));
    }
    const auto begin = Clock::now();  // the recording is not timed
    batch.Step(actions.data(), obs.data(), rewards.data(), terminated.data(), truncated.data(),
               terms.data());
    seconds += Seconds(begin);
  }
  return seconds;
}

// [s] for the bare physics of the same flights: `n` copies of the scene in the same threads,
// one call per environment step as the environment makes them; each world starts each step
// from the state the environment's world had then and holds its rotor commands over the step's
// MuJoCo steps (mj_step alone: no control, no observation, no reward), so that the physics runs
// through the same attitudes and contacts as the environment's (a tilted, turning vehicle
// costs MuJoCo more than one at rest). A step the environment spent resetting has no physics.
double TimeBarePhysics(const EnvParams& params, int n, int threads,
                       const std::vector<PhysicsState>& states) {
  const Map map = FindEnvTask(params.task).map(params);
  const Simulation scene = Simulation::FromXml(EnvSceneXml(params, map), "env");
  const mjModel* m = scene.model();
  if (m->nq != 7 || m->nv != 6 || m->na != 4 || m->nu != 4) {
    throw std::logic_error("rl bench: the scene is not one free vehicle with four rotors");
  }
  std::vector<Simulation> sims;
  for (int i = 0; i < n; ++i) sims.push_back(scene.Clone());
  const long physics = std::lround(1.0 / (params.control_rate * scene.timestep()));
  const long steps = static_cast<long>(states.size()) / n;
  WorkerPool pool(std::min(threads, n));
  const auto begin = Clock::now();
  for (long s = 0; s < steps; ++s) {
    pool.For(n, [&](int from, int to) {
      for (int i = from; i < to; ++i) {
        const PhysicsState& state = states[static_cast<size_t>(s * n + i)];
        if (state.reset) continue;
        Simulation& sim = sims[static_cast<size_t>(i)];
        mjData* d = sim.mutable_data();
        std::copy(state.qpos.begin(), state.qpos.end(), d->qpos);
        std::copy(state.qvel.begin(), state.qvel.end(), d->qvel);
        std::copy(state.act.begin(), state.act.end(), d->act);
        std::copy(state.ctrl.begin(), state.ctrl.end(), d->ctrl);
        for (long k = 0; k < physics; ++k) mj_step(sim.model(), d);
      }
    });
  }
  return Seconds(begin);
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// One table row: `n` worlds of `params`, the environment against the bare physics.
void Row(std::ostream& out, const std::string& label, const EnvParams& params, int n, int threads,
         const BenchSize& size) {
  const long steps = size.smoke ? 5 : std::max(100L, 40000L / n);
  std::vector<double> env, bare;
  std::vector<PhysicsState> states;
  for (int r = 0; r < size.Repetitions(3); ++r) {
    env.push_back(TimeEnvironment(params, n, threads, steps, &states));
    bare.push_back(TimeBarePhysics(params, n, threads, states));
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
      << " threads; the bare physics: the same flights' MuJoCo steps alone (mj_step from "
      << "the state each world had at each environment step, its rotor commands held; one "
      << "call per environment step, in the same threads). Medians of " << size.Repetitions(3)
      << ".\n\n| worlds" << header;
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
