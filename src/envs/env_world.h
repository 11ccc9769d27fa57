// One world of a learning environment: its own physics (MuJoCo's data, or the rigid body), the
// vehicle's world below the
// action (mission/flight_parts.h: the inner loops at the physics rate), and the task
// (env_task.h): a seeded random start, the observation, the reward and how an episode ends.
// Worlds share nothing, so a batch (env_batch.h) steps many in threads and each gives what it
// would alone.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "control/controller.h"
#include "control/position_control.h"
#include "envs/env_params.h"
#include "envs/env_task.h"
#include "mission/flight.h"
#include "mission/flight_parts.h"
#include "sim/vehicle_physics.h"

namespace aerobox {

// What one step gave.
struct EnvStep {
  double reward = 0.0;
  bool terminated = false;    // crashed, touched anything, left the bounds, not finite
  bool truncated = false;     // the episode's time is up
  std::vector<double> terms;  // the reward's terms (EnvParams::RewardTermNames), summing to it
};

// The command an action of every level but "velocity" asks for (docs/learning.md's scaling):
// `a` holds ActionSize values, each in [-1, 1].
ControlCommand ActionCommand(const EnvParams& params, const QuadParams& vehicle, const double* a);

class EnvWorld {
 public:
  // `physics`: this world's own physics of the environment's scene, made from `map` (the task
  // kind's). Throws std::invalid_argument for bad parameters.
  EnvWorld(const EnvParams& params, std::unique_ptr<VehiclePhysics> physics, const Map& map);

  // A new episode from a random start, from the world's stream seeded with `seed` when given
  // (else going on from the last), with reset's options. Writes the observation
  // (ObservationSize floats). Throws std::invalid_argument for options the task refuses.
  void Reset(std::optional<std::uint64_t> seed, float* observation, const EnvOptions& options = {});
  // One step of `action` (ActionSize values, each in [-1, 1], finite: the caller checks), held
  // over the control period. Writes the observation after it.
  EnvStep Step(const double* action, float* observation);

  // Step in its parts, for a batch that steps its worlds' physics together (EnvBatch): Begin;
  // while Stepping(), BeforePhysics, the physics' step with the rotor commands it returns [N],
  // AfterPhysics; then End. Step is exactly these with the world's own physics.
  void Begin(const double* action);
  bool Stepping() const { return substep_ < steps_per_control_ && !touched_; }
  const Vec4& BeforePhysics();
  void AfterPhysics();
  EnvStep End(const double* action, float* observation);

  // The command an action asks for (docs/learning.md's scaling); a velocity action runs the
  // velocity loop once.
  ControlCommand CommandOf(const double* action);
  double time() const { return t_; }             // [s] into the episode
  const State& state() const { return state_; }  // the truth
  const State& seen() const { return seen_; }    // the observation's: with sensors, the estimate
  const EnvTask& task() const { return *task_; }
  const VehicleWorld& vehicle_world() const { return *world_; }  // after a reset
  VehiclePhysics& physics() { return *physics_; }
  // The observation now (ObservationSize floats): what Reset and Step write.
  void Observe(float* observation) const;

 private:
  // Draws the episode's vehicle, wind and sensor noise (domain randomisation) from `seed`.
  void Vary(std::uint64_t seed);

  EnvParams params_;
  QuadParams vehicle_;
  std::unique_ptr<VehiclePhysics> physics_;
  std::unique_ptr<EnvTask> task_;
  FlightLoop loop_;
  std::optional<VehicleWorld> world_;
  bool velocity_;       // the action is a velocity: velocity_loop_ turns it into an attitude
  CommandLevel level_;  // params_.action, parsed once
  PositionController velocity_loop_;
  long steps_per_control_;
  EnvRandom random_;
  double t_ = 0.0;
  State state_;  // the truth
  State seen_;   // what the vehicle knows: the truth, or the estimate with sensors on
  std::array<double, 4> last_action_{};
  // the step under way (Begin to End)
  ControlCommand command_;
  State truth_;
  long substep_ = 0;
  bool touched_ = false;
};

}  // namespace aerobox
