// N worlds of one learning environment stepped in one call, in threads over blocks of worlds,
// with Gymnasium 1.x's vector semantics (autoreset on the next step): the arrays in and out
// are the Python module's numpy buffers, so no Python runs per world. World i seeded with s + i
// gives exactly what a lone world seeded with s + i gives, whatever the number of threads.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/worker_pool.h"
#include "envs/env_params.h"
#include "envs/env_world.h"
#include "sim/rigid_batch.h"
#include "sim/simulation.h"

namespace aerobox {

class EnvBatch {
 public:
  // `worlds` >= 1 of `params`' environment; `threads` >= 1 (the caller's included). Throws
  // std::invalid_argument for bad parameters.
  EnvBatch(const EnvParams& params, int worlds, int threads);

  int size() const { return static_cast<int>(worlds_.size()); }
  const EnvParams& params() const { return params_; }

  // Every world anew; world i from seeds[i] when it has one. `observations`: size() x
  // ObservationSize floats.
  // `options` (reset's) apply to every world; std::invalid_argument when the task refuses them.
  void Reset(const std::vector<std::optional<std::uint64_t>>& seeds, float* observations,
             const EnvOptions& options = {});
  // The worlds `indices` anew, each going on from its own stream (as an autoreset does); their
  // observations into `observations` (indices.size() x ObservationSize floats), in that order.
  // For the same-step autoreset of other vector APIs (stable-baselines3's). Throws
  // std::out_of_range for an index outside the batch.
  void ResetSome(const std::vector<int>& indices, float* observations);
  // One step of every world: `actions` size() x ActionSize, each finite and within [-1, 1]
  // (else std::invalid_argument naming the world and the component, before any world steps).
  // A world whose episode ended at the last step is reset instead (its action ignored, reward
  // 0, neither flag set), from its own stream. `terms`: size() x term_count() reward terms.
  void Step(const double* actions, float* observations, double* rewards, std::uint8_t* terminated,
            std::uint8_t* truncated, double* terms);

  EnvWorld& world(int i) { return *worlds_[static_cast<size_t>(i)]; }
  // MuJoCo's scene showing world i as it is now (to render it): the world's own simulation,
  // or with the rigid backend one shared simulation placed in the world's state.
  Simulation& Showing(int i);
  int observation_size() const { return observation_size_; }
  int term_count() const { return term_count_; }
  const Map& map() const { return map_; }

 private:
  EnvParams params_;
  Map map_;           // the task kind's, which every world flies in
  Simulation scene_;  // MuJoCo's model of it, as loaded: the worlds' template
  int observation_size_, term_count_;
  std::unique_ptr<RigidBatch> rigid_;  // the rigid backend's bodies, one world each
  std::vector<std::unique_ptr<EnvWorld>> worlds_;
  std::vector<std::uint8_t> ended_;  // the episode ended at the last step: reset at the next
  WorkerPool pool_;

  // One environment step of the worlds [begin, end) (a thread's block): each world's command,
  // then physics steps until every world's control period is over or it touched something,
  // each phase a loop over the block; the rigid backend steps the block's bodies together.
  void StepBlock(int begin, int end, const double* actions);
  // One physics step of the block's active worlds: each its own MuJoCo, or the rigid bodies in
  // runs of neighbours. False when no world was active.
  bool StepPhysics(int begin, int end);
  // World i's physics steps now: its episode goes on and its control period is not over. Read,
  // not kept: flags of neighbouring worlds written by two threads would share a cache line.
  bool Active(int i) const {
    return !ended_[static_cast<size_t>(i)] && worlds_[static_cast<size_t>(i)]->Stepping();
  }
};

// The scene every world of `params` flies in: the task kind's map (an empty room around the
// target, a map of boxes) with the floor.
std::string EnvSceneXml(const EnvParams& params, const Map& map);

}  // namespace aerobox
