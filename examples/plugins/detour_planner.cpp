// An example planner plug-in: the straight line when it is free, else a detour through one
// waypoint beside the line's middle, tried at growing offsets to either side (and above); no
// path when none within `max_offset` is free. Its offsets are scenario keys:
//
//   [planner]
//   kind = "example_detour"
//   step = 0.25        # [m]
//   max_offset = 5.0   # [m]
//
// It registers itself when aerobox starts; nothing under src/ names it.
#include <chrono>
#include <memory>
#include <utility>
#include <vector>

#include "common/schema.h"
#include "planning/path_simplify.h"
#include "planning/planner.h"

namespace {

using aerobox::Archive;
using aerobox::Vec3;

struct DetourParams {
  double step = 0.25;       // [m]
  double max_offset = 5.0;  // [m]

  void Describe(Archive& a) {
    a.Number({"step", "m", "how much further aside each detour tried goes"}, &step, 0.01, 10);
    a.Number({"max_offset", "m", "the farthest aside a detour may go"}, &max_offset, 0.01, 1000);
  }
};

class DetourPlanner : public aerobox::Planner {
 public:
  DetourPlanner(const DetourParams& params, const aerobox::PlannerContext& context)
      : params_(params), context_(context) {}

  aerobox::PlanResult Plan(const Vec3& start, const Vec3& goal) override {
    const auto begin = std::chrono::steady_clock::now();
    aerobox::PlanResult result = Search(start, goal);
    result.stats.planning_time =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    return result;
  }

 private:
  aerobox::PlanResult Search(const Vec3& start, const Vec3& goal) const {
    const aerobox::Validity& valid = context_.validity;
    aerobox::PlanResult result;
    if (!valid.state(start)) {
      result.status = aerobox::PlanStatus::kStartInvalid;
      return result;
    }
    if (!valid.state(goal)) {
      result.status = aerobox::PlanStatus::kGoalInvalid;
      return result;
    }
    if (valid.motion(start, goal)) return Solved({start, goal});
    const Vec3 middle = 0.5 * (start + goal);
    Vec3 aside = (goal - start).cross(Vec3::UnitZ());
    aside = aside.norm() > 1e-9 ? aside.normalized() : Vec3::UnitX();
    for (double offset = params_.step; offset <= params_.max_offset; offset += params_.step) {
      for (const Vec3& direction : {aside, Vec3(-aside), Vec3(Vec3::UnitZ())}) {
        ++result.stats.iterations;
        const Vec3 via = middle + offset * direction;
        if (valid.state(via) && valid.motion(start, via) && valid.motion(via, goal)) {
          aerobox::PlanResult solved = Solved({start, via, goal});
          solved.stats.iterations = result.stats.iterations;
          return solved;
        }
      }
    }
    result.status = aerobox::PlanStatus::kNoPathWithinBudget;
    return result;
  }

  static aerobox::PlanResult Solved(std::vector<Vec3> path) {
    aerobox::PlanResult result;
    result.status = aerobox::PlanStatus::kSolved;
    result.path = std::move(path);
    result.stats.final_cost = aerobox::PathLength(result.path);
    return result;
  }

  DetourParams params_;
  aerobox::PlannerContext context_;
};

[[maybe_unused]] const bool kRegistered = [] {
  aerobox::Planners().Register(
      "example_detour",
      [](const aerobox::PlannerConfig& config, const aerobox::PlannerContext& context) {
        return std::make_unique<DetourPlanner>(config.params.Get<DetourParams>(), context);
      },
      aerobox::PluginParameters::Of(DetourParams()));
  return true;
}();

}  // namespace
