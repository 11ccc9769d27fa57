// OMPL 1.5.2's RRT* wired to aerobox's collision world: built only for benchmarks
// (-DAEROBOX_WITH_OMPL=ON), never part of what users run.
#include <ompl/base/MotionValidator.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/util/Console.h>

#include <chrono>

#include "bench/planner_comparison.h"
#include "common/stop.h"

namespace aerobox {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

Vec3 ToVec(const ob::State* state) {
  const auto* s = state->as<ob::RealVectorStateSpace::StateType>();
  return Vec3(s->values[0], s->values[1], s->values[2]);
}

// The exact segment test as OMPL's motion validator: the same validity both planners see.
class ExactMotionValidator : public ob::MotionValidator {
 public:
  ExactMotionValidator(const ob::SpaceInformationPtr& si, const CollisionWorld& world)
      : ob::MotionValidator(si), world_(world) {}
  bool checkMotion(const ob::State* a, const ob::State* b) const override {
    const bool valid = world_.IsSegmentFree(ToVec(a), ToVec(b));
    valid ? ++valid_ : ++invalid_;
    return valid;
  }
  bool checkMotion(const ob::State*, const ob::State*,
                   std::pair<ob::State*, double>&) const override {
    throw std::logic_error("RRTstar does not ask for the last valid state");
  }

 private:
  const CollisionWorld& world_;
};

}  // namespace

bool HaveOmpl() { return true; }

AnytimeRun RunOmpl(const CollisionWorld& world, const PlanningProblem& problem, double seconds,
                   bool informed) {
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  auto space = std::make_shared<ob::RealVectorStateSpace>(3);
  ob::RealVectorBounds bounds(3);
  for (int k = 0; k < 3; ++k) {
    bounds.setLow(k, world.free_bounds().min[k]);
    bounds.setHigh(k, world.free_bounds().max[k]);
  }
  space->setBounds(bounds);
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker([&world](const ob::State* s) { return world.IsPointFree(ToVec(s)); });
  si->setMotionValidator(std::make_shared<ExactMotionValidator>(si, world));
  si->setup();

  ob::ScopedState<> start(space), goal(space);
  for (int k = 0; k < 3; ++k) {
    start[k] = problem.start[k];
    goal[k] = problem.goal[k];
  }
  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  pdef->setStartAndGoalStates(start, goal, 1e-9);
  pdef->setOptimizationObjective(std::make_shared<ob::PathLengthOptimizationObjective>(si));

  auto planner = std::make_shared<og::RRTstar>(si);
  // the same settings as ours: range 0.2 x the diagonal (OMPL's default), goal bias 0.05,
  // rewire factor 1.1, k-nearest rewiring
  planner->setRange(0.2 * world.free_bounds().Size().norm());
  planner->setGoalBias(0.05);
  planner->setRewireFactor(1.1);
  planner->setKNearest(true);
  planner->setInformedSampling(informed);
  planner->setProblemDefinition(pdef);
  planner->setup();

  AnytimeRun run;
  const auto begin = std::chrono::steady_clock::now();
  pdef->setIntermediateSolutionCallback(
      [&](const ob::Planner*, const std::vector<const ob::State*>&, const ob::Cost cost) {
        const double now =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
        if (run.time_to_first < 0) run.time_to_first = now;
        run.history.emplace_back(now, cost.value());
      });
  // its time budget, or Ctrl-C (common/stop.h)
  const ob::PlannerStatus status = planner->solve(ob::plannerOrTerminationCondition(
      ob::timedPlannerTerminationCondition(seconds),
      ob::PlannerTerminationCondition([] { return StopRequested(); })));
  ThrowIfStopRequested("planning with OMPL's RRT*");
  run.iterations = static_cast<long>(planner->numIterations());
  if (status == ob::PlannerStatus::EXACT_SOLUTION) {
    const double now =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    auto path = std::static_pointer_cast<og::PathGeometric>(pdef->getSolutionPath());
    // a straight start-goal solution may come without a callback
    if (run.time_to_first < 0) {
      run.time_to_first = now;
      run.history.emplace_back(now, path->length());
    }
    og::PathSimplifier simplifier(si);
    og::PathGeometric simplified(*path);
    simplifier.shortcutPath(simplified, 100);
    simplifier.reduceVertices(simplified);
    run.simplified_cost = simplified.length();
  }
  return run;
}

}  // namespace aerobox
