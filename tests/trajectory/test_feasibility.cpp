// What a vehicle can fly, by differential flatness, and the minimum-time allocation that holds a
// trajectory to it.
#include <doctest/doctest.h>

#include <cmath>

#include "geometry/collision_world.h"
#include "trajectory/feasibility.h"
#include "trajectory/trajectory_generator.h"

namespace aerobox {
namespace {

// A Tello-sized X quadrotor: 80 g, rotors 3.5 cm out on each axis, 0.4 N each, numbered as
// RotorPy (front-left, then clockwise seen from above).
FlatnessLimits Tello() {
  FlatnessLimits v;
  v.mass = 0.08;
  v.inertia = Vec3(7.1e-5, 7.5e-5, 1.24e-4);
  const double d = 0.035, k = 0.006;
  const double x[4] = {d, d, -d, -d}, y[4] = {d, -d, -d, d}, dir[4] = {1, -1, 1, -1};
  for (int i = 0; i < 4; ++i) v.allocation.col(i) << 1.0, y[i], -x[i], dir[i] * k;
  v.min_rotor_thrust = 0.0;
  v.max_rotor_thrust = 0.4;
  v.max_tilt = 0.5;
  v.max_rate = 6.0;
  v.max_speed = 8.0;
  v.max_vertical_speed = 3.0;
  return v;
}

// One segment per dimension polynomial p(t) = c0 + c1 t + ... over `duration` (coefficients in
// real time, converted to the segments' normalised time).
PiecewiseTrajectory Polynomial(const std::vector<Vec3>& real, double duration) {
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(3, kCoefficients);
  for (size_t k = 0; k < real.size(); ++k) c.col(k) = real[k] * std::pow(duration, k);
  return PiecewiseTrajectory({PolynomialSegment(c, duration)});
}

TrajectoryWorld Open() {
  return {[](const Aabb&) { return true; }, [](const Vec3&, const Vec3&) { return true; }};
}

}  // namespace

TEST_CASE("flatness: hover, a steady acceleration and a jerk give the thrust, tilt and rates") {
  const FlatnessLimits tello = Tello();
  // hovering: nothing is asked of anything but the weight
  const PiecewiseTrajectory hover = Polynomial({Vec3(1, 2, 3)}, 2.0);
  CHECK(CheckFeasibility(hover, tello, 0.01).ratio == doctest::Approx(0.0));

  // a steady 3 m/s^2 along x: the tilt is atan(3 / g), and its ratio tan(tilt) / tan(0.5)
  const PiecewiseTrajectory steady = Polynomial({Vec3::Zero(), Vec3::Zero(), Vec3(1.5, 0, 0)}, 1.0);
  const FeasibilityCheck tilt = CheckFeasibility(steady, tello, 0.01);
  CHECK(tilt.limit == "tilt");
  CHECK(tilt.ratio == doctest::Approx((3.0 / kGravity) / std::tan(0.5)).epsilon(1e-9));
  CHECK(tilt.scale == doctest::Approx(std::sqrt(tilt.ratio)));

  // a jerk of 20 m/s^3 along x from rest: at t = 0 the body pitches at j / g (Mellinger and
  // Kumar's h_w), and the rotors' thrusts rise at the front-back pair's moment
  const PiecewiseTrajectory jerk =
      Polynomial({Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3(20.0 / 6.0, 0, 0)}, 0.01);
  FlatnessLimits rates_only = tello;
  rates_only.max_tilt = 1.4;  // so that the rate is what binds
  const FeasibilityCheck rate = CheckFeasibility(jerk, rates_only, 0.01, 0.0, 0.0);
  CHECK(rate.limit == "body rate");
  CHECK(rate.ratio == doctest::Approx(20.0 / kGravity / 6.0).epsilon(1e-6));

  // a rotor asked beyond its thrust: 2 g straight up needs 3 x the weight, 0.59 N per rotor
  // (for 0.1 s: below the vertical speed limit)
  const PiecewiseTrajectory up =
      Polynomial({Vec3::Zero(), Vec3::Zero(), Vec3(0, 0, kGravity)}, 0.1);
  const FeasibilityCheck rotors = CheckFeasibility(up, tello, 0.01);
  CAPTURE(rotors.limit);
  CAPTURE(rotors.t);
  CHECK(rotors.limit.find("thrust") != std::string::npos);
  const double hover_thrust = 0.08 * kGravity / 4;
  CHECK(rotors.ratio ==
        doctest::Approx((3 * hover_thrust - hover_thrust) / (0.4 - hover_thrust)).epsilon(1e-6));
  CHECK(rotors.ratio > 1.0);
}

TEST_CASE("min-time: every point within the vehicle's limits, faster than the snap objective") {
  const std::vector<Vec3> path = {Vec3(0, 0, 1), Vec3(6, 0, 1), Vec3(6, 5, 2), Vec3(12, 5, 2)};
  TrajectoryParams snap;
  snap.use_corridors = false;
  TrajectoryParams fast = snap;
  fast.objective = TimeObjective::kMinTime;
  fast.max_speed = std::numeric_limits<double>::infinity();
  fast.max_accel = std::numeric_limits<double>::infinity();
  fast.vehicle = Tello();
  const TrajectoryResult slow = GenerateTrajectory(path, Open(), snap);
  const TrajectoryResult quick = GenerateTrajectory(path, Open(), fast);
  REQUIRE(quick.status == TrajectoryStatus::kSolved);
  const FlatnessLimits limits = EffectiveLimits(fast);
  // the margins: a quarter of each rotor's swing kept for the controller
  CHECK(limits.max_rotor_thrust == doctest::Approx(0.4 - 0.25 * (0.4 - 0.08 * kGravity / 4)));
  const FeasibilityCheck worst = CheckFeasibility(quick.trajectory, limits, 0.001);
  CAPTURE(worst.limit);
  CHECK(worst.ratio <= 1.005);
  CHECK(worst.ratio > 0.9);  // and close to them: nothing is left on the table at the worst point
  CHECK(quick.stats.binding_limit.ratio == doctest::Approx(worst.ratio).epsilon(0.01));
  // the snap objective at its 2 m/s and 2 m/s^2 takes 13.9 s, min-time about 7
  CHECK(quick.stats.duration < 0.6 * slow.stats.duration);
}

TEST_CASE("min-time: a long straight leg cruises at the speed limit") {
  const std::vector<Vec3> path = {Vec3(0, 0, 5), Vec3(200, 0, 5)};
  TrajectoryParams params;
  params.use_corridors = false;
  params.objective = TimeObjective::kMinTime;
  params.max_speed = 6.0;  // a cap below the vehicle's 8 m/s
  params.vehicle = Tello();
  const TrajectoryResult result = GenerateTrajectory(path, Open(), params);
  REQUIRE(result.status == TrajectoryStatus::kSolved);
  CHECK(result.stats.max_speed <= 6.0 * 1.005);
  // most of the leg at more than 90 % of the cap: not one segment peaking in its middle
  int cruising = 0, samples = 0;
  for (double t = 0; t <= result.stats.duration; t += 0.05, ++samples) {
    if (result.trajectory.Evaluate3(t, kVelocity).norm() > 0.9 * 6.0) ++cruising;
  }
  CHECK(cruising > 0.8 * samples);
  // the point-mass time (200 m at 6 m/s, ramps at g tan 0.5) is within 20 %
  const double accel = kGravity * std::tan(0.5);
  CHECK(result.stats.duration < 1.2 * (200.0 / 6.0 + 6.0 / accel));
}

TEST_CASE("a continuing trajectory starts in the state it continues and ends at rest") {
  TrajectoryParams params;
  params.objective = TimeObjective::kMinTime;
  params.max_speed = params.max_accel = std::numeric_limits<double>::infinity();
  params.vehicle = Tello();
  StartState start;
  start.p_W = Vec3(0, 0, 1);
  start.v_W = Vec3(3, 1, 0);  // flying at 3.2 m/s, turning
  start.a_W = Vec3(-1, 2, 0.5);
  start.j_W = Vec3(0.5, 0, -2);
  const std::vector<Vec3> path = {start.p_W, Vec3(4, 3, 1.5), Vec3(2, 8, 1)};
  const TrajectoryResult r = ContinueTrajectory(start, path, Open(), params);
  REQUIRE(r.status == TrajectoryStatus::kSolved);
  const PiecewiseTrajectory& t = r.trajectory;
  CHECK((t.Evaluate3(0, kPosition) - start.p_W).norm() < 1e-9);
  CHECK((t.Evaluate3(0, kVelocity) - start.v_W).norm() < 1e-9);
  CHECK((t.Evaluate3(0, kAcceleration) - start.a_W).norm() < 1e-9);
  CHECK((t.Evaluate3(0, kJerk) - start.j_W).norm() < 1e-9);
  CHECK((t.Evaluate3(t.duration(), kPosition) - path.back()).norm() < 1e-9);
  CHECK(t.Evaluate3(t.duration(), kVelocity).norm() < 1e-9);
  CHECK(CheckFeasibility(t, EffectiveLimits(params), 0.001).ratio <= 1.005);
  // a wall across the first leg: midpoints until it passes, or an honest status
  const TrajectoryWorld walled{
      [](const Aabb&) { return true; },
      [](const Vec3& a, const Vec3& b) { return std::max(a.x(), b.x()) < 4.5; }};
  const TrajectoryResult bounded = ContinueTrajectory(start, path, walled, params);
  CHECK((bounded.status == TrajectoryStatus::kSolved ||
         bounded.status == TrajectoryStatus::kCollides));
  if (bounded.status == TrajectoryStatus::kSolved) {
    CHECK_FALSE(FirstCollisionTime(bounded.trajectory, walled, 0.01));
  }
}

TEST_CASE("a continuation from a start still accelerating into a turn is found in few solves") {
  // the forest case that took a replan 240 ms: 1.8 m/s and 3.4 m/s^2 forward, a turn ahead
  TrajectoryParams params;
  params.objective = TimeObjective::kMinTime;
  params.max_speed = params.max_accel = std::numeric_limits<double>::infinity();
  params.vehicle = Tello();
  StartState start;
  start.p_W = Vec3(4.3, 1.9, 2.5);
  start.v_W = Vec3(0.0, 1.8, 0.0);
  start.a_W = Vec3(0.0, 3.4, 0.9);
  start.j_W = Vec3(0.0, -4.0, 0.0);
  const std::vector<Vec3> path = {start.p_W, Vec3(4.6, 2.6, 2.5), Vec3(6.5, 3.2, 2.5),
                                  Vec3(6.8, 8.0, 2.5)};
  const TrajectoryResult r = ContinueTrajectory(start, path, Open(), params);
  REQUIRE(r.status == TrajectoryStatus::kSolved);
  CHECK(CheckFeasibility(r.trajectory, EffectiveLimits(params), 0.001).ratio <= 1.005);
  MESSAGE("solves: " << r.stats.solves << ", duration " << r.stats.duration << " s");
  CHECK(r.stats.solves <= 8);
}

}  // namespace aerobox
