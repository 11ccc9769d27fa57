// The trajectory-generator seam: a path (from a planner) in, a trajectory out, with a status.
// The built-ins, by name: "minsnap" (ours: corridors, Ipopt, refinement), the baselines
// "quintic", "cubic" and "septic-full" on min-snap's waypoints and times (baselines.h), and
// "given", a sampled trajectory from elsewhere (SampledTrajectory). A user's generator is one
// more.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/registry.h"
#include "trajectory/trajectory_generator.h"

namespace aerobox {

// One sample of a trajectory given from outside, as aerobox's trajectory.csv holds them.
struct TrajectorySample {
  double t = 0.0;           // [s] from the start
  Vec3 p_W = Vec3::Zero();  // [m]
  Vec3 v_W = Vec3::Zero();  // [m/s]
  Vec3 a_W = Vec3::Zero();  // [m/s^2]
};

// Quintic Hermite segments through the samples: positions, velocities and accelerations met at
// every sample, continuous up to acceleration. Throws std::invalid_argument for fewer than two
// samples, times that do not increase, or non-finite values.
PiecewiseTrajectory SampledTrajectory(const std::vector<TrajectorySample>& samples);

class TrajectoryGenerator {
 public:
  virtual ~TrajectoryGenerator() = default;
  // `path` is collision-free (as a planner returns it); its first and last points are where
  // the trajectory starts and ends at rest. Never throws for a path it cannot follow: a status.
  virtual TrajectoryResult Generate(const std::vector<Vec3>& path,
                                    const TrajectoryWorld& world) = 0;
  // From a state in motion (replanning: the setpoint where the new trajectory takes over) along
  // `path`, whose first point is start.p_W, to rest at its end. Nothing when the generator
  // cannot start in motion (the baselines, a given trajectory): the replanner then continues
  // with min-snap's.
  virtual std::optional<TrajectoryResult> Continue(const StartState& /*start*/,
                                                   const std::vector<Vec3>& /*path*/,
                                                   const TrajectoryWorld& /*world*/) {
    return std::nullopt;
  }
};

struct GeneratorConfig {
  std::string method = "minsnap";  // a name in TrajectoryGenerators()
  TrajectoryParams params;
  std::vector<TrajectorySample> given;  // method "given"
};

using GeneratorFactory =
    std::function<std::unique_ptr<TrajectoryGenerator>(const GeneratorConfig&)>;

Registry<GeneratorFactory>& TrajectoryGenerators();

// The generator `config.method` names; throws std::invalid_argument for an unknown one.
std::unique_ptr<TrajectoryGenerator> MakeGenerator(const GeneratorConfig& config);

}  // namespace aerobox
