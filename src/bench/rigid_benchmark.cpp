#include "bench/rigid_benchmark.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <memory>
#include <thread>
#include <vector>

#include "common/number_format.h"
#include "common/stop.h"
#include "common/wall_clock.h"
#include "common/worker_pool.h"
#include "control/inner_loops.h"
#include "envs/env_batch.h"
#include "envs/env_task.h"
#include "sim/rigid_batch.h"
#include "sim/simulation.h"

namespace aerobox {
namespace {

using Clock = std::chrono::steady_clock;

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// [s] of `steps` environment steps of `n` worlds (zero actions: thrust mid-range, no rates;
// episodes end and reset as in training), resets not timed.
double TimeSteps(const EnvParams& params, int n, int threads, long steps) {
  EnvBatch batch(params, n, threads);
  const size_t d = static_cast<size_t>(batch.observation_size());
  std::vector<float> obs(n * d);
  std::vector<double> actions(static_cast<size_t>(n * params.ActionSize()), 0.0), rewards(n),
      terms(static_cast<size_t>(n * batch.term_count()));
  std::vector<std::uint8_t> terminated(n), truncated(n);
  std::vector<std::optional<std::uint64_t>> seeds;
  for (int i = 0; i < n; ++i) seeds.emplace_back(i);
  batch.Reset(seeds, obs.data());
  const auto begin = Clock::now();
  for (long s = 0; s < steps; ++s) {
    ThrowIfStopRequested("timing the rigid backend");
    batch.Step(actions.data(), obs.data(), rewards.data(), terminated.data(), truncated.data(),
               terms.data());
  }
  return Seconds(begin);
}

// Environment steps per second, the median of the size's repetitions.
double Rate(const EnvParams& params, int n, int threads, const BenchSize& size) {
  const long steps = size.smoke ? 5 : std::max(100L, 200000L / n);
  std::vector<double> times;
  for (int r = 0; r < size.Repetitions(3); ++r)
    times.push_back(TimeSteps(params, n, threads, steps));
  return static_cast<double>(n) * steps / Median(times);
}

// [s] of the parts alone, in the same threads over `n` worlds: per world and physics step the
// rigid bodies' step (from hover, rotor commands varying about hover; each thread's block of
// worlds in one call, as the environments step them) and the inner loops (rates from hover); per
// world and environment step the action's command, the observation and the reward; a reset.
struct Parts {
  double dynamics = 0.0, inner = 0.0;                     // per physics step
  double command = 0.0, observation = 0.0, reward = 0.0;  // per environment step
  double reset = 0.0;                                     // per reset
};

// [s] per call of `fn(world)` over `calls` calls for each of `n` worlds, in `pool`'s threads.
template <typename Fn>
double PerCall(WorkerPool& pool, int n, long calls, Fn fn) {
  const auto begin = Clock::now();
  pool.For(n, [&](int from, int to) {
    for (int i = from; i < to; ++i) {
      for (long k = 0; k < calls; ++k) fn(i, k);
    }
  });
  return Seconds(begin) / (static_cast<double>(n) * calls);
}

// The environment's own parts: the command, the observation (the world's and the task's), the
// reward, a reset.
void TimeEnvironmentParts(const EnvParams& params, int n, int threads, long calls, Parts* parts) {
  EnvBatch batch(params, n, threads);
  const size_t d = static_cast<size_t>(batch.observation_size());
  std::vector<float> obs(n * d);
  std::vector<std::optional<std::uint64_t>> seeds;
  for (int i = 0; i < n; ++i) seeds.emplace_back(i);
  batch.Reset(seeds, obs.data());
  std::vector<std::unique_ptr<EnvTask>> tasks;  // to score, as each world's own task would
  for (int i = 0; i < n; ++i) {
    tasks.push_back(FindEnvTask(params.task).make(params, params.Vehicle(), batch.map()));
    EnvRandom random;
    random.Seed(static_cast<std::uint64_t>(i));
    tasks.back()->Begin(random, EnvOptions());
  }
  const double action[4] = {0.1, 0.0, 0.0, 0.0};
  WorkerPool pool(std::min(threads, n));
  parts->command = PerCall(pool, n, calls, [&](int i, long) { batch.world(i).CommandOf(action); });
  parts->observation =
      PerCall(pool, n, calls, [&](int i, long) { batch.world(i).Observe(obs.data() + i * d); });
  parts->reward = PerCall(pool, n, calls, [&](int i, long k) {
    tasks[static_cast<size_t>(i)]->Score(0.01 * k, batch.world(i).state(), action);
  });
  parts->reset = PerCall(pool, n, std::max(1L, calls / 100), [&](int i, long) {
    batch.world(i).Reset(std::nullopt, obs.data() + i * d);
  });
}

Parts TimeParts(const EnvParams& params, int n, int threads, long physics_steps) {
  const Map map = FindEnvTask(params.task).map(params);
  const RigidModel model = RigidModel::Of(Simulation::FromXml(EnvSceneXml(params, map), "env"));
  const QuadParams vehicle = params.Vehicle();
  const double hover = vehicle.HoverThrustPerRotor();
  RigidBatch bodies(model, n);
  std::vector<std::unique_ptr<InnerLoops>> loops;
  State start;
  start.p_W = params.target;
  for (int i = 0; i < n; ++i) {
    bodies.SetVehicleState(i, start);
    loops.push_back(std::make_unique<InnerLoops>(InnerLoopParams(), vehicle));
  }
  WorkerPool pool(std::min(threads, n));
  Parts parts;
  auto begin = Clock::now();
  pool.For(n, [&](int from, int to) {
    for (long k = 0; k < physics_steps; ++k) {
      for (int i = from; i < to; ++i) {
        bodies.SetCommands(i, Vec4::Constant(hover * (1.0 + 0.01 * (k % 7))));
      }
      bodies.Step(from, to);
    }
  });
  parts.dynamics = Seconds(begin) / (static_cast<double>(n) * physics_steps);
  begin = Clock::now();
  pool.For(n, [&](int from, int to) {
    ControlCommand command;  // each thread's own
    command.level = CommandLevel::kThrustRates;
    command.thrust = 4 * hover;
    InnerOutput out;
    for (int i = from; i < to; ++i) {
      for (long k = 0; k < physics_steps; ++k) {
        command.rate_B = Vec3(0.01 * (k % 5), 0.0, 0.0);
        loops[static_cast<size_t>(i)]->Run(command, bodies.VehicleState(i), 1e-3, &out);
      }
    }
  });
  parts.inner = Seconds(begin) / (static_cast<double>(n) * physics_steps);
  return parts;
}

// Where the rigid backend's time goes for `n` worlds: the parts timed alone against the step.
void WhereTimeGoes(const EnvParams& rigid, int n, int threads, const BenchSize& size,
                   std::ostream& out) {
  const int used = std::min(threads, n);
  const double env_rate = Rate(rigid, n, threads, size);
  const double per_env_step = used / env_rate;  // [s] of a thread per world and environment step
  const long physics = std::lround(rigid.physics_rate / rigid.control_rate);
  Parts parts = TimeParts(rigid, n, threads, size.smoke ? 10 : 20000);
  TimeEnvironmentParts(rigid, n, threads, size.smoke ? 10 : 2000, &parts);
  const double episode_steps = rigid.episode_time * rigid.control_rate;
  const auto share = [&](double seconds) { return 100.0 * seconds * used / per_env_step; };
  const double dynamics = share(parts.dynamics * physics), inner = share(parts.inner * physics),
               command = share(parts.command), observation = share(parts.observation),
               reward = share(parts.reward), reset = share(parts.reset / episode_steps);
  out << "\nWhere the rigid backend's time goes at " << n << " worlds and 1 ms (each part timed "
      << "alone in the same threads, from hover; per environment step of one world " << std::fixed
      << std::setprecision(2) << per_env_step * 1e6 << " us of a thread): " << std::setprecision(0)
      << "the dynamics " << dynamics << " % (" << std::setprecision(1)
      << parts.dynamics * used * 1e9 << " ns of a thread per world and physics step, each "
      << "thread's block of worlds stepped together), " << std::setprecision(0)
      << "the inner loops (rates, mixer) " << inner << " %, the action's command " << command
      << " %, the observation " << observation << " %, the reward " << reward << " %, resets "
      << "(one per " << episode_steps << " steps) " << reset << " %, the rest (the sensors' and "
      << "the air's calls, the loop over the physics steps, threads) "
      << 100 - dynamics - inner - command - observation - reward - reset << " %.\n"
      << std::defaultfloat << std::flush;
  // the forces of the air: drag, and a mean wind with Dryden turbulence, against still air
  EnvParams windy = rigid;
  windy.drag = true;
  windy.wind_speed = 3.0;
  windy.wind_turbulence = 1.0;
  const double windy_step = used / Rate(windy, n, threads, size);
  out << "With drag and wind (up to 3 m/s, Dryden turbulence up to 1 m/s) a step takes "
      << std::fixed << std::setprecision(2) << windy_step * 1e6 << " us of a thread: the air's "
      << "forces add " << std::setprecision(0) << 100 * (windy_step / per_env_step - 1)
      << " % to the still-air step.\n"
      << std::defaultfloat << std::flush;
}

}  // namespace

void RunRigidBenchmark(std::ostream& out, const BenchSize& size) {
  const int threads = std::max(1U, std::thread::hardware_concurrency());
  EnvParams mujoco;  // Hover-v0's defaults: the Crazyflie, 100 Hz, thrust and rates
  EnvParams rigid = mujoco;
  rigid.backend = "rigid";
  out << "aerobox/Hover-v0 at " << FormatNumber(mujoco.control_rate)
      << " Hz on the rigid backend (the vehicle "
      << "alone, integrated as MuJoCo integrates it) against MuJoCo's, " << threads
      << " threads, zero actions, episodes ending and resetting as in training; simulated "
         "seconds per wall second: environment steps per second over the control rate. Medians "
         "of "
      << size.Repetitions(3) << ".\n\n| worlds | physics step | MuJoCo: env steps/s | rigid: env "
      << "steps/s | rigid / MuJoCo | rigid: simulated s per wall s |\n|---|---|---|---|---|---|\n";
  const std::vector<int> sizes =
      size.smoke ? std::vector<int>{1, 4} : std::vector<int>{1, 64, 256, 1024};
  for (const int n : sizes) {
    const double a = Rate(mujoco, n, threads, size), b = Rate(rigid, n, threads, size);
    out << std::fixed << "| " << n << " | 1 ms | " << std::setprecision(0) << a << " | " << b
        << " | " << std::setprecision(1) << b / a << " | " << std::setprecision(0)
        << b / rigid.control_rate << " |\n"
        << std::defaultfloat << std::flush;
  }
  // at the peers' integration steps: crazyflow's 2 ms (500 Hz), L2F's 10 ms (100 Hz)
  for (const double rate : {500.0, 100.0}) {
    EnvParams coarse = rigid;
    coarse.physics_rate = rate;
    EnvParams coarse_mujoco = mujoco;
    coarse_mujoco.physics_rate = rate;
    for (const int n : {size.smoke ? 4 : 64, size.smoke ? 4 : 1024}) {
      const double a = Rate(coarse_mujoco, n, threads, size), b = Rate(coarse, n, threads, size);
      out << std::fixed << "| " << n << " | " << std::setprecision(0) << 1000.0 / rate << " ms | "
          << a << " | " << b << " | " << std::setprecision(1) << b / a << " | "
          << std::setprecision(0) << b / coarse.control_rate << " |\n"
          << std::defaultfloat << std::flush;
    }
  }
  WhereTimeGoes(rigid, sizes.back(), threads, size, out);
}

}  // namespace aerobox
