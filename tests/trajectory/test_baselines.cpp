#include <doctest/doctest.h>

#include <cmath>

#include "trajectory/baselines.h"
#include "trajectory/min_snap.h"
#include "trajectory/time_allocation.h"

namespace aerobox {
namespace {

std::vector<Vec3> Waypoints() {
  return {Vec3(0, 0, 1), Vec3(2, 0.5, 1.5), Vec3(3, 2.5, 1), Vec3(1.5, 4, 2), Vec3(4, 5, 1.2)};
}

std::vector<double> Durations() { return TrapezoidDurations(Waypoints(), 2.0, 2.0); }

// |jump| of derivative r at the end of segment i
double Jump(const PiecewiseTrajectory& t, size_t i, int r) {
  const auto& s = t.segments();
  return (s[i].Evaluate(s[i].duration(), r) - s[i + 1].Evaluate(0.0, r)).norm();
}

void CheckPositions(const PiecewiseTrajectory& t) {
  const std::vector<Vec3> w = Waypoints();
  REQUIRE(t.segments().size() + 1 == w.size());
  for (size_t i = 0; i < t.segments().size(); ++i) {
    CHECK((t.segments()[i].Evaluate(0.0, kPosition) - w[i]).norm() < 1e-9);
    CHECK((t.segments()[i].Evaluate(t.segments()[i].duration(), kPosition) - w[i + 1]).norm() <
          1e-9);
  }
}

}  // namespace

TEST_CASE("quintic: the stated velocity and acceleration at each knot, and jerk jumps") {
  const std::vector<Vec3> w = Waypoints();
  const std::vector<double> d = Durations();
  const PiecewiseTrajectory t = QuinticTrajectory(w, d);
  CheckPositions(t);
  for (size_t i = 1; i + 1 < w.size(); ++i) {
    CAPTURE(i);
    const Vec3 in = (w[i] - w[i - 1]) / d[i - 1], out = (w[i + 1] - w[i]) / d[i];
    CHECK((t.segments()[i].Evaluate(0.0, kVelocity) - 0.5 * (in + out)).norm() < 1e-9);
    CHECK((t.segments()[i].Evaluate(0.0, kAcceleration) - (out - in) / (0.5 * (d[i - 1] + d[i])))
              .norm() < 1e-9);
    CHECK(Jump(t, i - 1, kVelocity) < 1e-9);
    CHECK(Jump(t, i - 1, kAcceleration) < 1e-9);
    CHECK(Jump(t, i - 1, kJerk) > 1e-3);  // what those users found: no more continuity
  }
  CHECK(t.segments().front().Evaluate(0.0, kVelocity).norm() < 1e-12);
  CHECK(t.segments().back().Evaluate(d.back(), kAcceleration).norm() < 1e-9);
}

TEST_CASE("cubic: a clamped spline, velocity and acceleration continuous, and jerk jumps") {
  const PiecewiseTrajectory t = CubicSplineTrajectory(Waypoints(), Durations());
  CheckPositions(t);
  for (size_t i = 0; i + 1 < t.segments().size(); ++i) {
    CAPTURE(i);
    CHECK(Jump(t, i, kVelocity) < 1e-9);
    CHECK(Jump(t, i, kAcceleration) < 1e-9);
    CHECK(Jump(t, i, kJerk) > 1e-3);
    CHECK(t.segments()[i].Evaluate(0.5, kSnap).norm() < 1e-9);  // degree 3
  }
  CHECK(t.segments().front().Evaluate(0.0, kVelocity).norm() < 1e-12);
  CHECK(t.segments().back().Evaluate(t.segments().back().duration(), kVelocity).norm() < 1e-12);
}

TEST_CASE("septic-full: continuous to the 6th derivative, equal to a direct solve") {
  const std::vector<Vec3> w = Waypoints();
  const std::vector<double> d = Durations();
  const PiecewiseTrajectory t = SepticFullTrajectory(w, d);
  CheckPositions(t);
  for (size_t i = 0; i + 1 < t.segments().size(); ++i) {
    for (int r = 1; r <= 6; ++r) {
      CAPTURE(i);
      CAPTURE(r);
      CHECK(Jump(t, i, r) < 1e-6 * (1.0 + t.segments()[i].Evaluate(d[i], r).norm()));
    }
  }
  for (int r = kVelocity; r <= kJerk; ++r) {
    CHECK(t.segments().front().Evaluate(0.0, r).norm() < 1e-9);
    CHECK(t.segments().back().Evaluate(d.back(), r).norm() < 1e-9);
  }
  // the same system written directly in each segment's own time t (monomials t^k), solved
  // densely: the curves agree
  const int n = static_cast<int>(d.size());
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(8 * n, 8 * n);
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(8 * n, 3);
  const auto monomial = [](double time, int r) {
    Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(8);
    for (int k = r; k < 8; ++k) {
      double f = 1.0;
      for (int j = 0; j < r; ++j) f *= k - j;
      row[k] = f * std::pow(time, k - r);
    }
    return row;
  };
  int row = 0;
  for (int i = 0; i < n; ++i) {
    a.block(row, 8 * i, 1, 8) = monomial(0.0, 0);
    b.row(row++) = w[i].transpose();
    a.block(row, 8 * i, 1, 8) = monomial(d[i], 0);
    b.row(row++) = w[i + 1].transpose();
  }
  for (int i = 1; i < n; ++i) {
    for (int r = 1; r <= 6; ++r) {
      a.block(row, 8 * (i - 1), 1, 8) = monomial(d[i - 1], r);
      a.block(row, 8 * i, 1, 8) = -monomial(0.0, r);
      ++row;
    }
  }
  for (int r = 1; r <= 3; ++r) {
    a.block(row++, 0, 1, 8) = monomial(0.0, r);
    a.block(row++, 8 * (n - 1), 1, 8) = monomial(d.back(), r);
  }
  REQUIRE(row == 8 * n);
  const Eigen::MatrixXd c = a.fullPivLu().solve(b);
  for (int i = 0; i < n; ++i) {
    for (double s = 0.0; s <= 1.0; s += 0.125) {
      Vec3 direct = Vec3::Zero();
      for (int k = 0; k < 8; ++k) direct += c.row(8 * i + k).transpose() * std::pow(s * d[i], k);
      CHECK((t.segments()[i].Evaluate(s * d[i], kPosition) - direct).norm() < 1e-8);
    }
  }
  // a finding, kept as a check: these are the optimality conditions of minimum snap with free
  // interior derivatives, so on the same times septic-full is the closed-form minimum snap
  MinSnapProblem problem;
  problem.waypoints = w;
  problem.durations = d;
  const PiecewiseTrajectory snap = SolveMinSnapClosedForm(problem);
  for (double time = 0.0; time <= t.duration(); time += 0.05) {
    CHECK((snap.Evaluate3(time, kPosition) - t.Evaluate3(time, kPosition)).norm() < 1e-8);
  }
}

TEST_CASE("method names") {
  for (const char* name : {"minsnap", "quintic", "cubic", "septic-full"}) {
    REQUIRE(ParseTrajectoryMethod(name));
    CHECK(std::string(ToString(*ParseTrajectoryMethod(name))) == name);
  }
  CHECK_FALSE(ParseTrajectoryMethod("septic"));
}

}  // namespace aerobox

#include "trajectory/generators.h"

namespace aerobox {

TEST_CASE("a sampled trajectory meets every sample's position, velocity and acceleration") {
  // samples of a known curve, unevenly spaced
  const auto p = [](double t) { return Vec3(std::sin(t), t * t, 0.5 * t); };
  const auto v = [](double t) { return Vec3(std::cos(t), 2 * t, 0.5); };
  const auto a = [](double t) { return Vec3(-std::sin(t), 2.0, 0.0); };
  std::vector<TrajectorySample> samples;
  for (const double t : {0.0, 0.3, 0.35, 1.0, 1.7}) samples.push_back({t, p(t), v(t), a(t)});
  const PiecewiseTrajectory trajectory = SampledTrajectory(samples);
  REQUIRE(trajectory.segments().size() == 4);
  CHECK(trajectory.duration() == doctest::Approx(1.7));
  for (const TrajectorySample& s : samples) {
    CAPTURE(s.t);
    // at the knots, from either side (1e-9: rounding of the normalised-time polynomials)
    for (const double t : {s.t - 1e-12, s.t + 1e-12}) {
      if (t < 0 || t > 1.7) continue;
      CHECK((trajectory.Evaluate3(t, kPosition) - s.p_W).norm() < 1e-9);
      CHECK((trajectory.Evaluate3(t, kVelocity) - s.v_W).norm() < 1e-8);
      CHECK((trajectory.Evaluate3(t, kAcceleration) - s.a_W).norm() < 1e-7);
    }
  }
  // between the samples the curve stays near the one sampled (quintic interpolation error)
  CHECK((trajectory.Evaluate3(0.65, kPosition) - p(0.65)).norm() < 1e-3);
  CHECK_THROWS_AS(SampledTrajectory({samples[0]}), std::invalid_argument);
  std::vector<TrajectorySample> backwards = samples;
  backwards[2].t = 0.2;
  CHECK_THROWS_WITH_AS(SampledTrajectory(backwards), doctest::Contains("times must increase"),
                       std::invalid_argument);
}

TEST_CASE("trajectory generators by name") {
  for (const char* name : {"minsnap", "quintic", "cubic", "septic-full", "given"}) {
    CAPTURE(name);
    CHECK(TrajectoryGenerators().Find(name) != nullptr);
  }
  GeneratorConfig config;
  config.method = "nosuch";
  CHECK_THROWS_WITH_AS(MakeGenerator(config), doctest::Contains("unknown trajectory generator"),
                       std::invalid_argument);
}

}  // namespace aerobox
