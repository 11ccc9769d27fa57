// The closed loop flies the parts it is given: a user's rule and observer join the built-in
// ones, and the built-in ones can be left out, without a change to the loop.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "flight_test_util.h"
#include "mission/flight_parts.h"

namespace aerobox {
namespace {

using testing::FromFunction;
using testing::RoomAt;

// A climb of 2 m in 4 s from hover at 1 m.
Reference Climb() {
  return FromFunction(4.0, [](double t) { return Vec3(0, 0, 1.0 + 0.5 * t); });
}

// Ends the flight above a height [m] (a user's rule).
class CeilingRule : public FlightRule {
 public:
  explicit CeilingRule(double z) : z_(z) {}
  std::optional<FlightStatus> Judge(const FlightMoment& now) override {
    if (now.state.p_W.z() > z_) return FlightStatus::kTerminated;
    return std::nullopt;
  }

 private:
  double z_;
};

// Counts what it sees (a user's observer) and adds to the result's steps what it counted.
class Counter : public FlightObserver {
 public:
  void ControlStep(const TelemetrySample& sample, bool) override {
    ++rows;
    last_t = sample.t;
  }
  void PhysicsStep(const PhysicsStepSample& step) override {
    ++steps;
    CHECK(step.step == doctest::Approx(0.001));
  }
  void Finish(FlightResult* result) const override { result->message = "counted"; }
  long rows = 0;
  long steps = 0;
  double last_t = 0.0;
};

struct Flyer {
  QuadParams vehicle;
  ControllerConfig config;
  std::unique_ptr<Controller> controller = MakeController(config, vehicle);
  Simulation sim = RoomAt(Vec3(0, 0, 1));
  FlightLoop loop;
  Flyer() {
    loop.vehicle = &vehicle;
    loop.controller = controller.get();
    loop.control_rate = config.rate;
    loop.inner = config.inner;
  }
};

TEST_CASE("a user's rule and observer fly beside the built-in parts") {
  Flyer f;
  VehicleWorld world(f.loop, &f.sim);
  FlightParams params;
  StandardParts standard(Climb(), params, f.loop, &world);
  FlightParts parts = standard.parts();
  CeilingRule ceiling(2.0);
  Counter counter;
  parts.rules.insert(parts.rules.begin(), &ceiling);
  parts.observers.push_back(&counter);
  const FlightResult result = FlyTrajectory(Climb(), params, f.loop, parts);
  CHECK(result.status == FlightStatus::kTerminated);
  CHECK(result.time == doctest::Approx(2.0).epsilon(0.05));  // 2 m at 0.5 m/s
  CHECK(counter.steps == result.steps);
  CHECK(counter.rows == result.steps / 4 + 1);         // 250 Hz of 1000 Hz, the last step's row too
  CHECK(result.time - counter.last_t < 0.004 + 1e-9);  // the rule judges every physics step
  CHECK(result.message == "counted");
  CHECK(result.distance == doctest::Approx(1.0).epsilon(0.05));  // the metrics observed too
}

TEST_CASE("without the built-in time limit, the flight ends by the user's rule") {
  Flyer f;
  VehicleWorld world(f.loop, &f.sim);
  FlightParams params;
  params.settle_time = 0.5;
  f.loop.completion.kind = Completion::Kind::kNever;  // no arrival either
  StandardParts standard(Climb(), params, f.loop, &world);
  FlightParts parts = standard.parts();
  // the standard rules: fly-away, arrival, the time limit (no terminate function given)
  REQUIRE(parts.rules.size() == 3);
  parts.rules.pop_back();
  struct Late : FlightRule {
    std::optional<FlightStatus> Judge(const FlightMoment& now) override {
      if (now.t >= 6.0) return FlightStatus::kTimeout;
      return std::nullopt;
    }
  } late;
  parts.rules.push_back(&late);
  const FlightResult result = FlyTrajectory(Climb(), params, f.loop, parts);
  // the built-in limit would have ended it at 4.5 s
  CHECK(result.status == FlightStatus::kTimeout);
  CHECK(result.time == doctest::Approx(6.0).epsilon(0.001));
}

TEST_CASE("a flight without a world or a take-off is refused") {
  Flyer f;
  FlightParts parts;
  CHECK_THROWS_AS(FlyTrajectory(Climb(), FlightParams(), f.loop, parts), std::invalid_argument);
}

}  // namespace
}  // namespace aerobox

namespace aerobox {
namespace {

// A slow, tight circle (radius 0.15 m at 0.3 m/s: its velocity turns at 2 rad/s), then a
// straight run along +y.
Reference TightTurnThenRun() {
  return testing::FromFunction(8.0, [](double t) {
    constexpr double kRadius = 0.15, kRate = 2.0;  // [m], [rad/s]
    if (t < 3.0) {
      return Vec3(kRadius * std::cos(kRate * t), kRadius * std::sin(kRate * t), 1.0);
    }
    const Vec3 end(kRadius * std::cos(kRate * 3.0), kRadius * std::sin(kRate * 3.0), 1.0);
    return Vec3(end + Vec3(0, 1.0 * (t - 3.0), 0));
  });
}

}  // namespace

TEST_CASE("yaw along the travel: turns at most yaw_rate, toward the reference look_ahead ahead") {
  FlightParams params;
  params.face_travel = true;
  params.yaw_rate = 1.0;  // [rad/s]
  Setpoints setpoints(TightTurnThenRun(), params, 0.0);
  constexpr double kStep = 0.004;  // [s]
  double previous = 0.0, fastest = 0.0;
  for (double t = 0.0; t < 3.0; t += kStep) {
    const FlatOutput s = setpoints.At(t, t);
    // a yaw along the velocity would turn at 2 rad/s here (and spin with any faster circle)
    fastest = std::max(fastest, std::abs(std::remainder(s.yaw - previous, 2 * M_PI)) / kStep);
    CHECK(std::abs(s.yaw_rate) <= params.yaw_rate + 1e-9);
    previous = s.yaw;
  }
  CHECK(fastest <= params.yaw_rate + 1e-6);
  // on the straight run, the yaw settles along +y, the way the reference goes 1 m ahead
  FlatOutput s;
  for (double t = 3.0; t < 7.0; t += kStep) s = setpoints.At(t, t);
  CHECK(std::abs(std::remainder(s.yaw - M_PI / 2, 2 * M_PI)) < 1e-6);
  // held: the yaw stays where it was
  params.face_travel = false;
  Setpoints held(TightTurnThenRun(), params, 0.3);
  CHECK(held.At(5.0, 5.0).yaw == doctest::Approx(0.3));
}

TEST_CASE(
    "yaw along the travel: from rest, the reference waits while the camera turns to its way") {
  FlightParams params;
  params.face_travel = true;
  // from rest at the origin, away along -x (behind a vehicle facing +x), smoothly
  const Reference behind = testing::FromFunction(4.0, [](double t) {
    const double s = std::min(t / 4.0, 1.0);
    return Vec3(-4.0 * s * s * s * (10 - 15 * s + 6 * s * s), 0, 1);
  });
  Setpoints setpoints(behind, params, 0.0);
  State at_rest;
  at_rest.p_W = Vec3(0, 0, 1);
  Takeoff clock(Vec3(0, 0, 1), at_rest, false);  // in the air: no lift
  constexpr double kStep = 0.004;                // [s]
  double first_move = -1.0;
  for (double t = 0.0; t < 3.0; t += kStep) {
    const double tr = clock.ReferenceTime(t, at_rest);
    const FlatOutput s = setpoints.At(t, tr);
    clock.Hold(setpoints.waiting());
    if (setpoints.waiting()) {
      CHECK(s.v_W.norm() == 0.0);  // held at rest while it turns
      CHECK(s.p_W.isApprox(Vec3(0, 0, 1)));
    }
    if (first_move < 0 && tr > 0.0) first_move = t;
  }
  // the yaw turns pi at yaw_rate (120 deg/s) and the clock runs again once it is within
  // turn_first (20 deg) of the way: after (180 - 20) / 120 s
  CHECK(first_move == doctest::Approx((M_PI - params.turn_first) / params.yaw_rate).epsilon(0.03));
  CHECK(clock.held() == doctest::Approx(first_move).epsilon(0.03));
  // with turn_first 180 deg it never waits
  params.turn_first = M_PI;
  Setpoints eager(behind, params, 0.0);
  eager.At(0.0, 0.0);
  CHECK_FALSE(eager.waiting());
}

}  // namespace aerobox
