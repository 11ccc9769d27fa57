#include "trajectory/generators.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "common/number_format.h"
#include "trajectory/baselines.h"

namespace aerobox {
namespace {

// Minimum snap with the corridors; when Ipopt fails on them (restoration failed, maximum
// iterations: seen on short legs between waypoints a centimetre apart), the closed form without
// corridors, whose collision-aware refinement inserts midpoints where it leaves free space.
// Only a trajectory that passes the exact check every 10 ms is returned as solved.
TrajectoryResult MinSnapWithFallback(const std::vector<Vec3>& path, const TrajectoryWorld& world,
                                     const TrajectoryParams& params) {
  TrajectoryResult result = GenerateTrajectory(path, world, params);
  const bool solver_failed =
      result.status == TrajectoryStatus::kFailed || result.status == TrajectoryStatus::kInfeasible;
  if (!solver_failed || !params.use_corridors || !params.closed_form_fallback) return result;
  TrajectoryParams closed = params;
  closed.use_corridors = false;
  TrajectoryResult fallback = GenerateTrajectory(path, world, closed);
  if (fallback.status != TrajectoryStatus::kSolved) return result;
  fallback.stats.solver_message =
      "closed form with refinement, after Ipopt: " + result.stats.solver_message;
  fallback.stats.closed_form_fallback = true;
  fallback.stats.solve_time += result.stats.solve_time;
  return fallback;
}

class MinSnapGenerator : public TrajectoryGenerator {
 public:
  explicit MinSnapGenerator(const TrajectoryParams& params) : params_(params) {}
  TrajectoryResult Generate(const std::vector<Vec3>& path, const TrajectoryWorld& world) override {
    return MinSnapWithFallback(path, world, params_);
  }
  std::optional<TrajectoryResult> Continue(const StartState& start, const std::vector<Vec3>& path,
                                           const TrajectoryWorld& world) override {
    return ContinueTrajectory(start, path, world, params_);
  }

 private:
  TrajectoryParams params_;
};

// A baseline on the same waypoints and segment times as min-snap's: only the polynomials
// differ (and the baselines do not look at obstacles).
class BaselineGenerator : public TrajectoryGenerator {
 public:
  BaselineGenerator(TrajectoryMethod method, const TrajectoryParams& params)
      : method_(method), params_(params) {}
  TrajectoryResult Generate(const std::vector<Vec3>& path, const TrajectoryWorld& world) override {
    TrajectoryResult result = MinSnapWithFallback(path, world, params_);
    if (result.status != TrajectoryStatus::kSolved) return result;
    const auto begin = std::chrono::steady_clock::now();
    result.trajectory =
        BaselineTrajectory(method_, result.waypoints, result.trajectory.SegmentDurations());
    result.corridors.assign(result.trajectory.segments().size(), std::nullopt);
    result.stats.solve_time =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    MeasureTrajectory(params_, &result);
    result.stats.solver_message = ToString(method_);
    return result;
  }

 private:
  TrajectoryMethod method_;
  TrajectoryParams params_;
};

// A trajectory from elsewhere: the path is not used; it is checked against the world.
class GivenGenerator : public TrajectoryGenerator {
 public:
  GivenGenerator(std::vector<TrajectorySample> samples, const TrajectoryParams& params)
      : samples_(std::move(samples)), params_(params) {}
  TrajectoryResult Generate(const std::vector<Vec3>&, const TrajectoryWorld& world) override {
    const auto begin = std::chrono::steady_clock::now();
    TrajectoryResult result;
    result.trajectory = SampledTrajectory(samples_);
    for (const TrajectorySample& s : samples_) result.waypoints.push_back(s.p_W);
    result.corridors.assign(result.trajectory.segments().size(), std::nullopt);
    const std::optional<double> hit =
        FirstCollisionTime(result.trajectory, world, params_.check_step);
    result.status = hit ? TrajectoryStatus::kCollides : TrajectoryStatus::kSolved;
    result.stats.solver_message =
        hit ? "the given trajectory leaves free space at t = " + FormatNumber(*hit) + " s"
            : "given";
    result.stats.segments = static_cast<int>(result.trajectory.segments().size());
    MeasureTrajectory(params_, &result);
    result.stats.solve_time =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    return result;
  }

 private:
  std::vector<TrajectorySample> samples_;
  TrajectoryParams params_;
};

}  // namespace

PiecewiseTrajectory SampledTrajectory(const std::vector<TrajectorySample>& samples) {
  if (samples.size() < 2) throw std::invalid_argument("a trajectory needs at least 2 samples");
  std::vector<PolynomialSegment> segments;
  for (size_t i = 0; i + 1 < samples.size(); ++i) {
    const TrajectorySample& a = samples[i];
    const TrajectorySample& b = samples[i + 1];
    const double T = b.t - a.t;
    if (!(T > 0) || !std::isfinite(T)) {
      throw std::invalid_argument("trajectory sample " + std::to_string(i + 1) +
                                  ": times must increase (t = " + FormatNumber(b.t) + " s)");
    }
    for (const TrajectorySample* s : {&a, &b}) {
      if (!s->p_W.allFinite() || !s->v_W.allFinite() || !s->a_W.allFinite()) {
        throw std::invalid_argument("trajectory sample at t = " + FormatNumber(s->t) +
                                    " s is not finite");
      }
    }
    // quintic Hermite in normalised time s = t / T: derivatives scale by T^r
    const Vec3 dp = b.p_W - a.p_W;
    const Vec3 v0 = T * a.v_W, v1 = T * b.v_W;
    const Vec3 a0 = T * T * a.a_W, a1 = T * T * b.a_W;
    Eigen::MatrixXd c = Eigen::MatrixXd::Zero(3, kCoefficients);
    c.col(0) = a.p_W;
    c.col(1) = v0;
    c.col(2) = 0.5 * a0;
    c.col(3) = 10 * dp - 6 * v0 - 4 * v1 - 1.5 * a0 + 0.5 * a1;
    c.col(4) = -15 * dp + 8 * v0 + 7 * v1 + 1.5 * a0 - a1;
    c.col(5) = 6 * dp - 3 * v0 - 3 * v1 - 0.5 * a0 + 0.5 * a1;
    segments.emplace_back(c, T);
  }
  return PiecewiseTrajectory(std::move(segments));
}

Registry<GeneratorFactory>& TrajectoryGenerators() {
  static Registry<GeneratorFactory> registry = [] {
    Registry<GeneratorFactory> r;
    r.Register("minsnap", [](const GeneratorConfig& config) {
      return std::make_unique<MinSnapGenerator>(config.params);
    });
    for (const TrajectoryMethod method :
         {TrajectoryMethod::kQuintic, TrajectoryMethod::kCubic, TrajectoryMethod::kSepticFull}) {
      r.Register(ToString(method), [method](const GeneratorConfig& config) {
        return std::make_unique<BaselineGenerator>(method, config.params);
      });
    }
    r.Register("given", [](const GeneratorConfig& config) {
      return std::make_unique<GivenGenerator>(config.given, config.params);
    });
    return r;
  }();
  return registry;
}

std::unique_ptr<TrajectoryGenerator> MakeGenerator(const GeneratorConfig& config) {
  const GeneratorFactory* factory = TrajectoryGenerators().Find(config.method);
  if (factory == nullptr) {
    throw std::invalid_argument("unknown trajectory generator '" + config.method + "' (expected " +
                                TrajectoryGenerators().NameList() + ")");
  }
  return (*factory)(config);
}

}  // namespace aerobox
