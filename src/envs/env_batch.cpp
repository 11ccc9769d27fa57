#include "envs/env_batch.h"

#include <cmath>
#include <stdexcept>

#include "common/number_format.h"
#include "map/map.h"
#include "scene/scene_mjcf.h"
#include "sim/rigid_body.h"

namespace aerobox {

std::string EnvSceneXml(const EnvParams& params, const Map& map) {
  SceneOptions options;
  options.vehicle_position = map.bounds.Center();
  options.timestep = 1.0 / params.physics_rate;
  options.offscreen_width = 640;
  options.offscreen_height = 480;
  return BuildSceneMjcf(map, params.Vehicle(), options);
}

namespace {

EnvParams Validated(const EnvParams& params) {
  params.Validate();
  return params;
}

}  // namespace

EnvBatch::EnvBatch(const EnvParams& params, int worlds, int threads)
    : params_(Validated(params)),
      map_(FindEnvTask(params_.task).map(params_)),
      scene_(Simulation::FromXml(EnvSceneXml(params_, map_), "env")),
      pool_(std::max(1, std::min(threads, worlds))) {
  if (worlds < 1)
    throw std::invalid_argument("EnvBatch: at least one world, got " + std::to_string(worlds));
  observation_size_ = params_.ObservationSize();
  term_count_ = static_cast<int>(params_.RewardTermNames().size());
  if (params_.backend == "rigid")
    rigid_ = std::make_unique<RigidBatch>(RigidModel::Of(scene_), worlds);
  for (int i = 0; i < worlds; ++i) {
    std::unique_ptr<VehiclePhysics> physics;
    if (rigid_) {
      physics = std::make_unique<RigidBody>(rigid_.get(), i);
    } else {
      physics = std::make_unique<Simulation>(scene_.Clone());
    }
    worlds_.push_back(std::make_unique<EnvWorld>(params_, std::move(physics), map_));
  }
  ended_.assign(static_cast<size_t>(worlds), 0);
}

Simulation& EnvBatch::Showing(int i) {
  VehiclePhysics& physics = world(i).physics();
  if (auto* own = dynamic_cast<Simulation*>(&physics)) return *own;
  scene_.SetVehicleState(physics.VehicleState());
  scene_.SetProducedThrusts(physics.RotorThrusts());
  return scene_;
}

void EnvBatch::Reset(const std::vector<std::optional<std::uint64_t>>& seeds, float* observations,
                     const EnvOptions& options) {
  worlds_.front()->task().Check(options);  // before any world changes
  const int d = observation_size_;
  pool_.For(size(), [&](int begin, int end) {
    for (int i = begin; i < end; ++i) {
      const auto seed =
          static_cast<size_t>(i) < seeds.size() ? seeds[static_cast<size_t>(i)] : std::nullopt;
      worlds_[static_cast<size_t>(i)]->Reset(seed, observations + static_cast<long>(i) * d,
                                             options);
      ended_[static_cast<size_t>(i)] = 0;
    }
  });
}

void EnvBatch::ResetSome(const std::vector<int>& indices, float* observations) {
  const int d = observation_size_;
  for (int i : indices) {
    if (i < 0 || i >= size()) {
      throw std::out_of_range("world " + std::to_string(i) + " of " + std::to_string(size()));
    }
  }
  pool_.For(static_cast<int>(indices.size()), [&](int begin, int end) {
    for (int j = begin; j < end; ++j) {
      const auto i = static_cast<size_t>(indices[static_cast<size_t>(j)]);
      worlds_[i]->Reset(std::nullopt, observations + static_cast<long>(j) * d);
      ended_[i] = 0;
    }
  });
}

void EnvBatch::Step(const double* actions, float* observations, double* rewards,
                    std::uint8_t* terminated, std::uint8_t* truncated, double* terms) {
  const int k = params_.ActionSize(), d = observation_size_, n_terms = term_count_;
  for (int i = 0; i < size(); ++i) {
    for (int j = 0; j < k; ++j) {
      const double a = actions[i * k + j];
      if (!(a >= -1.0 && a <= 1.0)) {
        throw std::invalid_argument("action[" + std::to_string(i) + "][" + std::to_string(j) +
                                    "] = " + FormatNumber(a) + ": expected a number in [-1, 1]");
      }
    }
  }
  pool_.For(size(), [&](int begin, int end) {
    StepBlock(begin, end, actions);
    for (int i = begin; i < end; ++i) {
      EnvWorld& w = *worlds_[static_cast<size_t>(i)];
      float* obs = observations + static_cast<long>(i) * d;
      EnvStep step;
      if (ended_[static_cast<size_t>(i)]) {
        w.Reset(std::nullopt, obs);
      } else {
        step = w.End(actions + static_cast<long>(i) * k, obs);
      }
      ended_[static_cast<size_t>(i)] = step.terminated || step.truncated;
      rewards[i] = step.reward;
      terminated[i] = step.terminated;
      truncated[i] = step.truncated;
      step.terms.resize(static_cast<size_t>(n_terms), 0.0);  // a reset scores nothing
      for (int j = 0; j < n_terms; ++j) terms[i * n_terms + j] = step.terms[static_cast<size_t>(j)];
    }
  });
}

void EnvBatch::StepBlock(int begin, int end, const double* actions) {
  const int k = params_.ActionSize();
  for (int i = begin; i < end; ++i) {
    if (!ended_[static_cast<size_t>(i)]) worlds_[static_cast<size_t>(i)]->Begin(actions + i * k);
  }
  while (StepPhysics(begin, end)) {
    for (int i = begin; i < end; ++i) {
      if (Active(i)) worlds_[static_cast<size_t>(i)]->AfterPhysics();
    }
  }
}

bool EnvBatch::StepPhysics(int begin, int end) {
  bool any = false;
  for (int i = begin; i < end; ++i) {
    if (!Active(i)) continue;
    any = true;
    EnvWorld& w = *worlds_[static_cast<size_t>(i)];
    if (rigid_) {
      rigid_->SetCommands(i, w.BeforePhysics());
    } else {
      w.physics().Step(w.BeforePhysics());
    }
  }
  if (!rigid_) return any;
  for (int i = begin; i < end;) {  // each run of active neighbours in one call
    int j = i;
    while (j < end && Active(j)) ++j;
    if (j > i) rigid_->Step(i, j);
    i = j + 1;
  }
  return any;
}

}  // namespace aerobox
