// One world of a learning environment: its own MuJoCo data, the vehicle's world below the
// action (mission/flight_parts.h: the inner loops at the physics rate), and the task: a seeded
// random start, the observation, the reward and how an episode ends. Worlds share nothing, so
// a batch (env_batch.h) steps many in threads and each gives what it would alone.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "control/controller.h"
#include "envs/env_params.h"
#include "mission/flight.h"
#include "mission/flight_parts.h"
#include "sim/simulation.h"

namespace aerobox {

// What one step gave.
struct EnvStep {
  double reward = 0.0;
  bool terminated = false;        // crashed, touched anything, left the bounds, not finite
  bool truncated = false;         // the episode's time is up
  std::array<double, 5> terms{};  // the reward's terms (RewardTermNames), summing to it
};

class EnvWorld {
 public:
  // `sim`: this world's own simulation of the environment's scene. Throws
  // std::invalid_argument for bad parameters.
  EnvWorld(const EnvParams& params, Simulation sim);

  // A new episode from a random start, from the world's stream seeded with `seed` when given
  // (else going on from the last). Writes the observation (ObservationSize floats).
  void Reset(std::optional<std::uint64_t> seed, float* observation);
  // One step of `action` (ActionSize values, each in [-1, 1], finite: the caller checks), held
  // over the control period. Writes the observation after it.
  EnvStep Step(const double* action, float* observation);

  // The command an action asks for (docs/learning.md's scaling).
  ControlCommand CommandOf(const double* action) const;
  double time() const { return t_; }  // [s] into the episode
  const State& state() const { return state_; }
  Simulation& sim() { return sim_; }

 private:
  void Observe(float* observation) const;
  State RandomStart();
  double Uniform();  // [0, 1), the same on every platform
  Vec3 InBall(double radius);

  EnvParams params_;
  QuadParams vehicle_;
  Simulation sim_;
  FlightLoop loop_;
  std::optional<VehicleWorld> world_;
  CommandLevel level_;  // params_.action, parsed once
  long steps_per_control_;
  std::mt19937_64 rng_;
  double t_ = 0.0;
  State state_;
  std::array<double, 4> last_action_{};
};

}  // namespace aerobox
