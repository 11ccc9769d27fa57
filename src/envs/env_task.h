// A learning environment's task: what an episode asks of the vehicle. The world (env_world.h)
// owns the physics, the action's command and the parts of the observation every task shares
// (position minus the task's reference point, velocity, attitude, body rates, the last action);
// a task draws the episode's start and whatever it needs (a target, a trajectory, a goal in a
// map), names the point the vehicle should be at, adds its own observation components after the
// shared ones, and scores each step. Built-in: hover, track, navigate (env_tasks.cpp); a user's
// task is registered by name and picked with EnvParams::task, without editing src/.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "common/state.h"
#include "common/types.h"
#include "envs/env_params.h"
#include "map/map.h"

namespace aerobox {

// A world's random stream: the same numbers on every platform.
class EnvRandom {
 public:
  void Seed(std::uint64_t seed);
  std::uint64_t Next() { return rng_(); }
  double Uniform();                         // [0, 1)
  double Uniform(double low, double high);  // [low, high)
  Vec3 InBall(double radius);               // uniform in the ball of `radius`
  // The start's attitude and body rate as EnvParams draws them: a random yaw, a tilt up to
  // start_tilt about a random horizontal axis, a body rate uniform in the ball of start_rate.
  void Attitude(const EnvParams& params, State* s);

 private:
  std::mt19937_64 rng_;
};

// What reset's options may set for one episode (Gymnasium's reset(options=...)).
struct EnvOptions {
  std::optional<Vec3> start;   // [m] the start's position (its velocity, attitude still drawn)
  std::optional<Vec3> target;  // [m] hover's target, navigate's goal
};

// One step's score.
struct TaskScore {
  std::vector<double> terms;  // the reward's terms, in the task's TermNames order
  bool ended = false;         // the task ends the episode (left the bounds, arrived)
};

class EnvTask {
 public:
  virtual ~EnvTask() = default;
  // Throws std::invalid_argument naming the option when this task cannot take `options` (by
  // default: a point not finite or not above the floor).
  virtual void Check(const EnvOptions& options) const;
  // A new episode: draws what it needs from `random`, applies `options` (checked), and returns
  // the start.
  virtual State Begin(EnvRandom& random, const EnvOptions& options) = 0;
  // Where the vehicle should be at time t [s] into the episode (world ENU, m).
  virtual Vec3 Reference(double t) const = 0;
  // The task's own observation components (ExtraNames' order) at time t.
  virtual void Observe(double t, const State& s, float* out) const = 0;
  // The step that ended at time t, in state s, after `action` (ActionSize values).
  virtual TaskScore Score(double t, const State& s, const double* action) = 0;
};

// A task kind in the registry.
struct EnvTaskKind {
  std::string name;  // EnvParams::task
  // The task's own observation components' names for these parameters.
  std::function<std::vector<std::string>(const EnvParams&)> extra_names;
  std::vector<std::string> term_names;  // the reward's terms, in order
  // The map the worlds fly in (the room around the target, a map's boxes); throws
  // std::invalid_argument naming the parameter when it cannot be made.
  std::function<Map(const EnvParams&)> map;
  // A task for one world of that map.
  std::function<std::unique_ptr<EnvTask>(const EnvParams&, const QuadParams&, const Map&)> make;
};

// Adds a kind (replacing one of the same name). Call before making environments.
void RegisterEnvTask(EnvTaskKind kind);
// The kind named `name`; std::invalid_argument listing the kinds when there is none.
const EnvTaskKind& FindEnvTask(const std::string& name);
std::vector<std::string> EnvTaskNames();

}  // namespace aerobox
