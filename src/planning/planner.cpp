#include "planning/planner.h"

#include <chrono>
#include <stdexcept>

#include "planning/path_simplify.h"

namespace aerobox {
namespace {

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
  WaypointsPlanner(std::vector<Vec3> waypoints, const PlannerContext& context)
      : waypoints_(std::move(waypoints)), context_(context) {}
  PlanResult Plan(const Vec3& start, const Vec3& goal) override {
    const auto begin = std::chrono::steady_clock::now();
    PlanResult result;
    result.path = {start};
    result.path.insert(result.path.end(), waypoints_.begin(), waypoints_.end());
    result.path.push_back(goal);
    result.status = PlanStatus::kSolved;
    for (size_t i = 0; i < result.path.size(); ++i) {
      if (!context_.validity.state(result.path[i]) ||
          (i > 0 && !context_.validity.motion(result.path[i - 1], result.path[i]))) {
        result.status = PlanStatus::kPathBlocked;
        result.stats.blocked_leg = static_cast<int>(i);
        result.path.clear();
        break;
      }
    }
    result.stats.iterations = 0;
    if (result.status == PlanStatus::kSolved) {
      result.stats.final_cost = result.stats.first_cost = PathLength(result.path);
      result.stats.time_to_first_solution = 0.0;
    }
    result.stats.planning_time =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    return result;
  }

 private:
  std::vector<Vec3> waypoints_;
  PlannerContext context_;
};

}  // namespace

Registry<PlannerFactory>& Planners() {
  static Registry<PlannerFactory> registry = [] {
    Registry<PlannerFactory> r;
    r.Register("rrt_star", [](const PlannerConfig& config, const PlannerContext& context) {
      return std::make_unique<RrtStarPlanner>(config.rrt, context);
    });
    r.Register("lattice", [](const PlannerConfig& config, const PlannerContext& context) {
      return std::make_unique<LatticeSeam>(config.lattice, context);
    });
    r.Register("waypoints", [](const PlannerConfig& config, const PlannerContext& context) {
      return std::make_unique<WaypointsPlanner>(config.waypoints, context);
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
  return (*factory)(config, context);
}

}  // namespace aerobox
