#include <doctest/doctest.h>

#include <cmath>
#include <numeric>

#include "common/stop.h"
#include "trajectory/min_snap.h"
#include "trajectory/time_allocation.h"

namespace aerobox {
namespace {

MinSnapProblem ZigZag(int segments) {
  MinSnapProblem problem;
  for (int i = 0; i <= segments; ++i) {
    problem.waypoints.emplace_back(i * 1.5, (i % 2) * 1.0, 1.0 + 0.3 * std::sin(i));
  }
  problem.durations = TrapezoidDurations(problem.waypoints, 2.0, 2.0);
  return problem;
}

// integral of |snap|^2 by composite Simpson's rule on every segment
double NumericSnapCost(const PiecewiseTrajectory& trajectory, int intervals) {
  double cost = 0.0;
  for (const PolynomialSegment& segment : trajectory.segments()) {
    const double h = segment.duration() / intervals;
    for (int i = 0; i <= intervals; ++i) {
      const double w = (i == 0 || i == intervals) ? 1 : (i % 2 == 1 ? 4 : 2);
      cost += w * h / 3.0 * segment.Evaluate(i * h, kSnap).squaredNorm();
    }
  }
  return cost;
}

void CheckKnots(const MinSnapProblem& problem, const PiecewiseTrajectory& trajectory) {
  const std::vector<PolynomialSegment>& segments = trajectory.segments();
  REQUIRE(segments.size() == problem.durations.size());
  for (size_t i = 0; i < segments.size(); ++i) {
    CAPTURE(i);
    // waypoints met at both ends of every segment; 1e-9 m is solver rounding
    CHECK((segments[i].Evaluate(0.0, kPosition) - problem.waypoints[i]).norm() < 1e-9);
    CHECK((segments[i].Evaluate(segments[i].duration(), kPosition) - problem.waypoints[i + 1])
              .norm() < 1e-9);
    if (i == 0) continue;
    // continuity of velocity .. snap, relative to the derivative's size
    for (int r = kVelocity; r <= kSnap; ++r) {
      const Eigen::VectorXd before = segments[i - 1].Evaluate(segments[i - 1].duration(), r);
      const Eigen::VectorXd after = segments[i].Evaluate(0.0, r);
      CHECK((before - after).norm() <= 1e-7 * (1.0 + before.norm()));
    }
  }
  // rest at both ends
  for (int r = kVelocity; r <= kJerk; ++r) {
    CHECK(segments.front().Evaluate(0.0, r).norm() < 1e-9);
    CHECK(segments.back().Evaluate(segments.back().duration(), r).norm() < 1e-9);
  }
}

}  // namespace

TEST_CASE("closed form: waypoints, continuity up to snap, rest at both ends") {
  for (const int segments : {1, 2, 5, 12}) {
    CAPTURE(segments);
    const MinSnapProblem problem = ZigZag(segments);
    CheckKnots(problem, SolveMinSnapClosedForm(problem));
  }
}

TEST_CASE("the analytic snap cost equals the integrated one") {
  const PiecewiseTrajectory trajectory = SolveMinSnapClosedForm(ZigZag(6));
  // Simpson's rule is exact for polynomials up to degree 3; snap^2 has degree 6, so the error
  // falls as h^4: 400 intervals per segment leave about 1e-9 of the cost
  const double analytic = trajectory.SnapCost();
  CHECK(analytic > 0);
  CHECK(NumericSnapCost(trajectory, 400) == doctest::Approx(analytic).epsilon(1e-7));
}

TEST_CASE("the allocation-free 3-d evaluation equals the general one") {
  const PiecewiseTrajectory trajectory = SolveMinSnapClosedForm(ZigZag(5));
  for (double t = -0.5; t <= trajectory.duration() + 0.5; t += 0.0371) {
    for (int d = kPosition; d <= kSnap; ++d) {
      CAPTURE(t);
      CAPTURE(d);
      CHECK((trajectory.Evaluate3(t, d) - trajectory.Evaluate(t, d)).norm() < 1e-12);
    }
  }
}

TEST_CASE("Ipopt without active inequalities equals the closed form to 1e-6") {
  MinSnapProblem problem = ZigZag(5);
  const PiecewiseTrajectory closed = SolveMinSnapClosedForm(problem);
  SUBCASE("no corridors") {}
  SUBCASE("corridors far away from the trajectory") {
    problem.corridors.assign(problem.durations.size(),
                             Aabb{Vec3::Constant(-100.0), Vec3::Constant(100.0)});
  }
  const MinSnapSolution solved = SolveMinSnapIpopt(problem);
  REQUIRE(solved.status == SolveStatus::kSolved);
  CheckKnots(problem, solved.trajectory);
  for (size_t i = 0; i < closed.segments().size(); ++i) {
    const Eigen::MatrixXd difference =
        solved.trajectory.segments()[i].coefficients() - closed.segments()[i].coefficients();
    CHECK(difference.cwiseAbs().maxCoeff() < 1e-6);
  }
}

TEST_CASE("a stop request (Ctrl-C) ends Ipopt at its next iteration, as Interrupted") {
  const MinSnapProblem problem = ZigZag(5);
  RequestStop();
  std::string during;
  try {
    SolveMinSnapIpopt(problem);
  } catch (const Interrupted& stop) {
    during = stop.during();
  }
  ClearStopRequest();
  CHECK(during == "solving the trajectory (Ipopt, minimum snap)");
  // and the closed form, which the time searches call hundreds of times
  RequestStop();
  CHECK_THROWS_AS(SolveMinSnapClosedForm(problem), Interrupted);
  ClearStopRequest();
  CHECK(SolveMinSnapIpopt(problem).status == SolveStatus::kSolved);  // nothing left over
}

TEST_CASE("Ipopt with corridors: samples stay inside, the cost rises, infeasible is reported") {
  MinSnapProblem problem;
  problem.waypoints = {Vec3(0, 0, 1), Vec3(2, 0, 1), Vec3(2, 2, 1), Vec3(0, 2, 1)};
  problem.durations = {2, 2, 2};
  const PiecewiseTrajectory free = SolveMinSnapClosedForm(problem);
  // tight boxes around each straight segment: the free optimum cuts the corners outside them
  problem.corridors = {Aabb{Vec3(-0.1, -0.1, 0.9), Vec3(2.1, 0.1, 1.1)},
                       Aabb{Vec3(1.9, -0.1, 0.9), Vec3(2.1, 2.1, 1.1)},
                       Aabb{Vec3(-0.1, 1.9, 0.9), Vec3(2.1, 2.1, 1.1)}};
  const MinSnapSolution solved = SolveMinSnapIpopt(problem);
  REQUIRE(solved.status == SolveStatus::kSolved);
  CheckKnots(problem, solved.trajectory);
  CHECK(solved.trajectory.SnapCost() > free.SnapCost());
  const auto& segments = solved.trajectory.segments();
  for (size_t i = 0; i < segments.size(); ++i) {
    for (int k = 1; k <= problem.samples_per_segment; ++k) {
      const Vec3 p = segments[i].Evaluate(
          segments[i].duration() * k / (problem.samples_per_segment + 1), kPosition);
      CHECK(problem.corridors[i]->Inflated(1e-7).Contains(p));  // Ipopt's tolerance
    }
  }
  // a corridor that excludes its own segment's end cannot be met
  problem.corridors[1] = Aabb{Vec3(1.9, -0.1, 0.9), Vec3(2.1, 1.0, 1.1)};
  problem.samples_per_segment = 40;
  const MinSnapSolution impossible = SolveMinSnapIpopt(problem);
  CHECK(impossible.status != SolveStatus::kSolved);
  CHECK_FALSE(impossible.message.empty());
}

TEST_CASE(
    "time refinement keeps the total, lowers the snap, and then the limits are reached sooner") {
  const MinSnapProblem start = ZigZag(6);
  const std::vector<double> refined = RefineDurations(start.waypoints, start.durations, 20);
  double before = 0, after = 0;
  for (size_t i = 0; i < refined.size(); ++i) {
    before += start.durations[i];
    after += refined[i];
    CHECK(refined[i] >= 0.05 * start.durations[i]);
  }
  CHECK(after == doctest::Approx(before).epsilon(1e-9));
  MinSnapProblem better = start;
  better.durations = refined;
  PiecewiseTrajectory old_times = SolveMinSnapClosedForm(start);
  PiecewiseTrajectory new_times = SolveMinSnapClosedForm(better);
  CHECK(new_times.SnapCost() < old_times.SnapCost());
  // scaled to the same limits, the refined times fly the same path in less time
  ScaleToLimits(2.0, 2.0, 0.002, &old_times);
  ScaleToLimits(2.0, 2.0, 0.002, &new_times);
  MESSAGE("durations at 2 m/s, 2 m/s^2: trapezoid " << old_times.duration() << " s, refined "
                                                    << new_times.duration() << " s");
  CHECK(new_times.duration() < old_times.duration());
}

TEST_CASE("the snap cost's gradient in the durations matches finite differences of the solve") {
  MinSnapProblem problem = ZigZag(7);
  // uneven durations, so the gradient is far from zero
  for (size_t i = 0; i < problem.durations.size(); ++i) problem.durations[i] *= 1.0 + 0.3 * (i % 3);
  const PiecewiseTrajectory optimum = SolveMinSnapClosedForm(problem);
  const std::vector<double> gradient = SnapCostGradient(optimum);
  REQUIRE(gradient.size() == problem.durations.size());
  for (size_t i = 0; i < gradient.size(); ++i) {
    CAPTURE(i);
    const double h = 1e-5 * problem.durations[i];
    MinSnapProblem longer = problem, shorter = problem;
    longer.durations[i] += h;
    shorter.durations[i] -= h;
    const double numeric =
        (SolveMinSnapClosedForm(longer).SnapCost() - SolveMinSnapClosedForm(shorter).SnapCost()) /
        (2.0 * h);
    CHECK(gradient[i] == doctest::Approx(numeric).epsilon(1e-5));
    CHECK(gradient[i] < 0.0);  // longer segments, less snap
  }
}

TEST_CASE("refined durations keep their sum and lower the cost, also for 150 segments") {
  for (const int segments : {6, 150}) {
    CAPTURE(segments);
    MinSnapProblem problem = ZigZag(segments);
    const double before = SolveMinSnapClosedForm(problem).SnapCost();
    const double total = std::accumulate(problem.durations.begin(), problem.durations.end(), 0.0);
    problem.durations = RefineDurations(problem.waypoints, problem.durations, 20);
    CHECK(std::accumulate(problem.durations.begin(), problem.durations.end(), 0.0) ==
          doctest::Approx(total).epsilon(1e-12));
    CHECK(SolveMinSnapClosedForm(problem).SnapCost() < (segments < 10 ? 0.8 : 0.95) * before);
  }
}

TEST_CASE("trapezoid times and the uniform time scale to the limits") {
  CHECK(TrapezoidTime(4.0, 2.0, 2.0) == doctest::Approx(3.0));             // cruise: 4/2 + 2/2
  CHECK(TrapezoidTime(1.0, 2.0, 2.0) == doctest::Approx(std::sqrt(2.0)));  // triangle
  PiecewiseTrajectory trajectory = SolveMinSnapClosedForm(ZigZag(5));
  const Vec3 start = trajectory.Evaluate(0.5, kPosition);
  const double factor = ScaleToLimits(1.5, 1.0, 0.002, &trajectory);
  CHECK(factor > 0);
  const double speed = trajectory.MaxNorm(kVelocity, 0.002);
  const double accel = trajectory.MaxNorm(kAcceleration, 0.002);
  CHECK(speed <= 1.5 + 1e-9);
  CHECK(accel <= 1.0 + 1e-9);
  // one of them is binding
  CHECK((speed == doctest::Approx(1.5) || accel == doctest::Approx(1.0)));
  // the same path in space
  CHECK((trajectory.Evaluate(0.5 * factor, kPosition) - start).norm() < 1e-12);
}

}  // namespace aerobox

namespace aerobox {

TEST_CASE(
    "a degenerate system is a status from Ipopt's solve and a typed error from the closed form") {
  // a segment of 1e-150 s: its basis rows overflow, the KKT system has no finite solution
  MinSnapProblem problem = ZigZag(3);
  problem.durations[1] = 1e-150;
  CHECK_THROWS_AS(SolveMinSnapClosedForm(problem), SingularSystem);
  problem.corridors.assign(problem.durations.size(), std::nullopt);
  MinSnapSolution solution;
  CHECK_NOTHROW(solution = SolveMinSnapIpopt(problem));
  CHECK(solution.status == SolveStatus::kFailed);
  CHECK(solution.message.find("minimum-snap system") != std::string::npos);
}

}  // namespace aerobox
