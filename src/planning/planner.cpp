#include "planning/planner.h"

#include <chrono>
#include <stdexcept>

#include "planning/lattice_planner.h"
#include "planning/path_simplify.h"
#include "planning/rrt_star.h"

namespace aerobox {

const char* ToString(PlanStatus status) {
  switch (status) {
    case PlanStatus::kSolved:
      return "solved";
    case PlanStatus::kNoPathWithinBudget:
      return "no path within budget";
    case PlanStatus::kStartInvalid:
      return "start invalid";
    case PlanStatus::kGoalInvalid:
      return "goal invalid";
    case PlanStatus::kPathBlocked:
      return "the given path is not free";
  }
  return "?";
}

namespace {

// Halvings of a blocked leg to find where it first leaves free space: 2^-20 of its length
constexpr int kBlockedBisections = 20;

class RrtStarPlanner : public Planner {
 public:
  RrtStarPlanner(const RrtStarParams& params, const PlannerContext& context)
      : params_(params), context_(context) {
    params_.seed = context.seed;
    params_.Validate();
  }
  PlanResult Plan(const Vec3& start, const Vec3& goal) override {
    return PlanRrtStar(start, goal, context_.bounds, context_.validity, params_);
  }

 private:
  RrtStarParams params_;
  PlannerContext context_;
};

// The lattice is built once, when the planner is made, and serves every query.
class LatticeSeam : public Planner {
 public:
  LatticeSeam(LatticeParams params, const PlannerContext& context)
      : planner_(context.bounds, context.validity, WithSeed(params, context.seed)) {}
  PlanResult Plan(const Vec3& start, const Vec3& goal) override {
    PlanResult result = planner_.Plan(start, goal);
    result.stats.nodes = planner_.stats().nodes;
    result.stats.edges = planner_.stats().edges;
    result.stats.build_time = planner_.stats().build_time;
    return result;
  }

 private:
  static LatticeParams WithSeed(LatticeParams params, std::uint64_t seed) {
    params.seed = seed;
    return params;
  }
  LatticePlanner planner_;
};

// A path given point by point: checked, not searched.
class WaypointsPlanner : public Planner {
 public:
  WaypointsPlanner(const WaypointsParams& params, const PlannerContext& context)
      : waypoints_(params.points), context_(context) {}
  PlanResult Plan(const Vec3& start, const Vec3& goal) override {
    const auto begin = std::chrono::steady_clock::now();
    std::vector<Vec3> path = {start};
    path.insert(path.end(), waypoints_.begin(), waypoints_.end());
    path.push_back(goal);
    PlanResult result = CheckGivenPath(std::move(path), context_.validity);
    result.stats.time_to_first_solution = result.status == PlanStatus::kSolved ? 0.0 : -1.0;
    result.stats.planning_time =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    return result;
  }

 private:
  std::vector<Vec3> waypoints_;
  PlannerContext context_;
};

}  // namespace

PlanResult CheckGivenPath(std::vector<Vec3> path, const Validity& validity) {
  PlanResult result;
  for (size_t i = 0; i < path.size(); ++i) {
    if (!validity.state(path[i])) {
      result.status = PlanStatus::kPathBlocked;
      result.stats.blocked_leg = static_cast<int>(i);
      result.stats.blocked_point = path[i];
      return result;
    }
    if (i > 0 && !validity.motion(path[i - 1], path[i])) {
      // where along the leg it first leaves free space: bisection on the exact segment check
      const Vec3 a = path[i - 1];
      const Vec3 d = path[i] - a;
      double free = 0.0, blocked = 1.0;
      for (int k = 0; k < kBlockedBisections; ++k) {
        const double mid = 0.5 * (free + blocked);
        (validity.motion(a, a + mid * d) ? free : blocked) = mid;
      }
      result.status = PlanStatus::kPathBlocked;
      result.stats.blocked_leg = static_cast<int>(i);
      result.stats.blocked_point = a + blocked * d;
      return result;
    }
  }
  result.status = PlanStatus::kSolved;
  result.stats.final_cost = result.stats.first_cost = PathLength(path);
  result.path = std::move(path);
  return result;
}

Registry<PlannerFactory>& Planners() {
  static Registry<PlannerFactory> registry = [] {
    Registry<PlannerFactory> r;
    r.Register("rrt_star", [](const PlannerConfig& config, const PlannerContext& context) {
      return std::make_unique<RrtStarPlanner>(config.params.GetOr<RrtStarParams>(), context);
    });
    r.Register("lattice", [](const PlannerConfig& config, const PlannerContext& context) {
      return std::make_unique<LatticeSeam>(config.params.GetOr<LatticeParams>(), context);
    });
    r.Register("waypoints", [](const PlannerConfig& config, const PlannerContext& context) {
      return std::make_unique<WaypointsPlanner>(config.params.GetOr<WaypointsParams>(), context);
    });
    return r;
  }();
  return registry;
}

std::unique_ptr<Planner> MakePlanner(const PlannerConfig& config, const PlannerContext& context) {
  const PlannerFactory* factory = Planners().Find(config.kind);
  if (factory == nullptr) {
    throw std::invalid_argument("unknown planner '" + config.kind + "' (expected " +
                                Planners().NameList() + ")");
  }
  if (!config.params.empty()) return (*factory)(config, context);
  PlannerConfig filled = config;  // a registered planner's defaults
  filled.params = Planners().Parameters(config.kind);
  return (*factory)(filled, context);
}

}  // namespace aerobox
