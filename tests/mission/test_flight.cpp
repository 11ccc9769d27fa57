// Closed-loop flights in MuJoCo with motor lag on: hover, a step, a circle, a figure-8, and a
// collision. The measured numbers are printed for the record.
#include <doctest/doctest.h>

#include <cmath>
#include <iostream>

#include "flight_test_util.h"
#include "mission/flight.h"

namespace aerobox {
namespace {

using testing::FromFunction;
using testing::RampedPhase;
using testing::RoomAt;
using testing::Track;

Track Fly(const Reference& reference, Simulation* sim, FlightParams params = FlightParams()) {
  Track track;
  params.settle_time = 3.0;
  track.result = FlyTrajectory(
      reference, params, QuadParams(), ControllerConfig(), {},
      [&track](const TelemetrySample& s) { track.samples.push_back(s); }, sim);
  return track;
}

}  // namespace

TEST_CASE("hover holds within 1 cm after 2 s") {
  // released 7 cm off the setpoint with the rotors at 90 % of hover thrust
  Simulation sim = RoomAt(Vec3(0.05, -0.05, 0.97));
  sim.SetRotorThrusts(Vec4::Constant(0.9 * QuadParams().HoverThrustPerRotor()));
  const Track track = Fly(FromFunction(5.0, [](double) { return Vec3(0, 0, 1); }), &sim);
  double worst = 0;
  for (const TelemetrySample& s : track.samples) {
    if (s.t >= 2.0) worst = std::max(worst, s.position_error);
  }
  std::cout << "hover: worst error after 2 s " << worst * 1e3 << " mm\n";
  CHECK(track.result.status == FlightStatus::kReachedGoal);
  CHECK(worst < 0.01);
}

TEST_CASE("a 1 m step settles within 2 s with less than 10 % overshoot") {
  Simulation sim = RoomAt(Vec3(0, 0, 1));
  const Track track = Fly(
      FromFunction(6.0, [](double t) { return t < 1.0 ? Vec3(0, 0, 1) : Vec3(1, 0, 1); }), &sim);
  double overshoot = 0;
  double settled_at = 0;  // last time outside 5 % of the step
  for (const TelemetrySample& s : track.samples) {
    if (s.t < 1.0) continue;
    overshoot = std::max(overshoot, s.state.p_W.x() - 1.0);
    if (std::abs(s.state.p_W.x() - 1.0) > 0.05) settled_at = s.t - 1.0;
  }
  std::cout << "step: overshoot " << overshoot * 100 << " %, settled within 5 % after "
            << settled_at << " s\n";
  CHECK(overshoot < 0.10);
  CHECK(settled_at < 2.0);
}

TEST_CASE("a 1 m circle at 1 m/s tracks with RMS under 3 cm") {
  // two laps at 1 rad/s on a 1 m radius (1 m/s), with 2 s ramps at both ends
  const double duration = 2.0 + 2 * 2 * M_PI;
  const auto circle = [duration](double t) {
    const double phase = RampedPhase(t, 1.0, 2.0, duration);
    return Vec3(std::cos(phase) - 1.0, std::sin(phase), 1.5);
  };
  Simulation sim = RoomAt(circle(0));
  const Track track = Fly(FromFunction(duration, circle), &sim);
  std::cout << "circle: RMS " << track.result.rms_error * 100 << " cm, max "
            << track.result.max_error * 100 << " cm\n";
  CHECK(track.result.status == FlightStatus::kReachedGoal);
  CHECK(track.result.rms_error < 0.03);
}

TEST_CASE("a figure-8 at up to 2 m/s tracks with RMS under 5 cm") {
  // x = A sin(w t), y = A/2 sin(2 w t): peak speed A w sqrt(1 + 1) at the crossing
  const double amplitude = 2.0;
  const double rate = 2.0 / (amplitude * std::sqrt(2.0));
  const double duration = 2.0 + 2 * M_PI / rate;  // one loop, 2 s ramps at both ends
  const auto eight = [=](double t) {
    const double phase = RampedPhase(t, rate, 2.0, duration);
    return Vec3(amplitude * std::sin(phase), 0.5 * amplitude * std::sin(2 * phase), 1.5);
  };
  Simulation sim = RoomAt(eight(0));
  const Track track = Fly(FromFunction(duration, eight), &sim);
  double top_speed = 0;
  for (const TelemetrySample& s : track.samples)
    top_speed = std::max(top_speed, s.setpoint.v_W.norm());
  std::cout << "figure-8: RMS " << track.result.rms_error * 100 << " cm, max "
            << track.result.max_error * 100 << " cm, top speed " << top_speed << " m/s\n";
  CHECK(top_speed == doctest::Approx(2.0).epsilon(0.02));
  CHECK(track.result.status == FlightStatus::kReachedGoal);
  CHECK(track.result.rms_error < 0.05);
}

TEST_CASE("a box on the path is a collision, not a success") {
  Map wall;
  wall.boxes.push_back({{Vec3(1, -2, 0), Vec3(1.2, 2, 6)}, Vec3(1, 0, 0), "wall", 1});
  Simulation sim = RoomAt(Vec3(0, 0, 1), wall);
  const Track track = Fly(
      FromFunction(3.0, [](double t) { return Vec3(std::min(1.0, t / 3.0) * 2.0, 0, 1); }), &sim);
  CHECK(track.result.status == FlightStatus::kCollision);
  CHECK(track.result.obstacle == "wall");
  CHECK(track.result.time < 3.0);
}

TEST_CASE("take-off from the floor is not a collision") {
  Simulation sim = RoomAt(Vec3(0, 0, 0.025));
  sim.SetRotorThrusts(Vec4::Zero());
  for (int i = 0; i < 100; ++i) sim.Step(Vec4::Zero());  // settle on the floor
  const Track track = Fly(
      FromFunction(3.0, [](double t) { return Vec3(0, 0, 0.125 + 0.5 * std::min(t / 3.0, 1.0)); }),
      &sim);
  CHECK(track.result.status == FlightStatus::kReachedGoal);
}

}  // namespace aerobox
