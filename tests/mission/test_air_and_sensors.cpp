// Flights in the air and on sensors: everything off is the ideal flight, wind pushes through
// drag, the estimator the controller flies on is consistent, the same seed repeats.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include "flight_test_util.h"
#include "mission/flight.h"
#include "mission/flight_parts.h"

namespace aerobox {
namespace {

using testing::Eight;
using testing::EightDuration;
using testing::FromFunction;
using testing::RoomAt;
using testing::Track;

// The figure-8 (or `reference`) with the cascade, with the loop's air and sensors set by `set`.
template <typename Setter>
Track FlyWith(const Reference& reference, const Vec3& start, Setter set) {
  Simulation sim = RoomAt(start);
  const QuadParams vehicle;
  const ControllerConfig config;
  const std::unique_ptr<Controller> controller = MakeController(config, vehicle);
  FlightLoop loop;
  loop.vehicle = &vehicle;
  loop.controller = controller.get();
  loop.control_rate = config.rate;
  loop.inner = config.inner;
  Track track;
  loop.telemetry = [&track](const TelemetrySample& s) { track.samples.push_back(s); };
  set(&loop);
  FlightParams params;
  params.settle_time = 3.0;
  track.result = FlyTrajectory(reference, params, loop, &sim);
  return track;
}

Reference EightReference() { return FromFunction(EightDuration(), Eight); }

SensorParams SensorsOn() {
  SensorParams s;
  s.imu.enabled = true;
  s.position.enabled = true;
  return s;
}

// Quantile of the chi-square distribution with k degrees of freedom (Wilson and Hilferty 1931;
// within 0.1 % for k in the hundreds). z: the standard normal quantile.
double ChiSquareQuantile(double k, double z) {
  const double a = 2.0 / (9.0 * k);
  return k * std::pow(1.0 - a + z * std::sqrt(a), 3);
}

}  // namespace

TEST_CASE("with no wind, no drag and no sensors the flight is the ideal one, step for step") {
  const Reference reference = EightReference();
  const Track ideal = FlyWith(reference, Eight(0), [](FlightLoop*) {});
  const Track off = FlyWith(reference, Eight(0), [](FlightLoop* loop) {
    loop->seed = 99;  // nothing seeded is on: the seed changes nothing
    loop->wind = WindParams();
    loop->aero = AeroParams();
    loop->sensors = SensorParams();
  });
  REQUIRE(ideal.samples.size() == off.samples.size());
  for (size_t i = 0; i < ideal.samples.size(); ++i) {
    REQUIRE(ideal.samples[i].state.p_W == off.samples[i].state.p_W);
    REQUIRE(ideal.samples[i].rotor_thrusts == off.samples[i].rotor_thrusts);
    REQUIRE_FALSE(off.samples[i].estimate.has_value());
  }
}

TEST_CASE("a steady wind pushes through drag, and the vehicle leans into it") {
  const Vec3 hold(0, 0, 1.5);
  const Track track =
      FlyWith(FromFunction(8.0, [&](double) { return hold; }), hold, [](FlightLoop* loop) {
        loop->wind.mean = Vec3(3, 0, 0);
        loop->aero = AeroParams{true, true};
      });
  const TelemetrySample& last = track.samples.back();
  // hovering in 3 m/s: body drag c 3^2 plus rotor drag k T 3, along the wind
  const QuadParams v;
  const double drag = v.body_drag.x() * 9 + v.rotor_drag.x() * v.mass * kGravity * 3;
  CHECK(last.wind_W.x() == doctest::Approx(3.0));
  CHECK(last.aero_force_W.x() == doctest::Approx(drag).epsilon(0.05));
  // the thrust tilts against the wind: body z leans towards -x by atan(drag / weight)
  const Vec3 z_B = last.state.q_WB * Vec3::UnitZ();
  const double lean = std::atan2(-z_B.x(), z_B.z());
  std::cout << "3 m/s wind: drag " << last.aero_force_W.x() << " N, lean " << lean
            << " rad, hold error " << last.position_error * 100 << " cm\n";
  CHECK(lean == doctest::Approx(std::atan(drag / (v.mass * kGravity))).epsilon(0.1));
  CHECK(last.position_error < 0.2);
  // without drag the same wind does nothing
  const Track still = FlyWith(FromFunction(3.0, [&](double) { return hold; }), hold,
                              [](FlightLoop* loop) { loop->wind.mean = Vec3(3, 0, 0); });
  CHECK(still.samples.back().aero_force_W.norm() == 0.0);
}

TEST_CASE("the estimator the controller flies on is consistent over 20 seeds") {
  // NEES (the 15-dimensional error weighted by the filter's covariance) averaged over N runs at
  // each control step: N times it is chi-square with 15 N degrees of freedom when the filter
  // is consistent (Bar-Shalom, Li and Kirubarajan 2001, 5.4). The figure-8 at up to 2 m/s,
  // IMU and motion capture at their defaults.
  constexpr int kRuns = 20;
  std::vector<std::vector<double>> nees(kRuns);
  double worst_rms = 0.0;
  for (int seed = 1; seed <= kRuns; ++seed) {
    const Track track = FlyWith(EightReference(), Eight(0), [seed](FlightLoop* loop) {
      loop->sensors = SensorsOn();
      loop->seed = static_cast<std::uint64_t>(seed);
    });
    REQUIRE(track.result.status == FlightStatus::kReachedGoal);
    worst_rms = std::max(worst_rms, track.result.estimate_rms_error);
    for (const TelemetrySample& s : track.samples) nees[seed - 1].push_back(s.estimate->nees);
  }
  size_t steps = nees[0].size();
  for (const std::vector<double>& run : nees) steps = std::min(steps, run.size());
  const double dof = 15.0 * kRuns;
  const double low = ChiSquareQuantile(dof, -1.96) / kRuns;  // the 95 % interval
  const double high = ChiSquareQuantile(dof, 1.96) / kRuns;
  int inside = 0;
  double mean = 0.0;
  for (size_t k = 0; k < steps; ++k) {
    double average = 0.0;
    for (const std::vector<double>& run : nees) average += run[k] / kRuns;
    inside += average >= low && average <= high;
    mean += average / static_cast<double>(steps);
  }
  const double fraction = static_cast<double>(inside) / static_cast<double>(steps);
  std::cout << "NEES over " << kRuns << " seeds: mean " << mean << " (15 expected), "
            << 100 * fraction << " % of " << steps << " steps within [" << low << ", " << high
            << "]; worst position RMS " << worst_rms * 1e3 << " mm\n";
  CHECK(fraction >= 0.90);
  CHECK(mean == doctest::Approx(15.0).epsilon(0.15));
  CHECK(worst_rms < 0.005);
}

TEST_CASE("the same seed gives the same turbulence and noise, byte for byte") {
  const auto fly = [](std::uint64_t seed) {
    return FlyWith(EightReference(), Eight(0), [seed](FlightLoop* loop) {
      loop->wind.mean = Vec3(2, 1, 0);
      loop->wind.turbulence = Turbulence::kDryden;
      loop->aero = AeroParams{true, true};
      loop->sensors = SensorsOn();
      loop->seed = seed;
    });
  };
  const Track a = fly(5), b = fly(5), c = fly(6);
  REQUIRE(a.samples.size() == b.samples.size());
  for (size_t i = 0; i < a.samples.size(); ++i) {
    REQUIRE(a.samples[i].state.p_W == b.samples[i].state.p_W);
    REQUIRE(a.samples[i].wind_W == b.samples[i].wind_W);
    REQUIRE(a.samples[i].estimate->imu.gyro_B == b.samples[i].estimate->imu.gyro_B);
  }
  CHECK(a.samples[100].wind_W != c.samples[100].wind_W);
  CHECK(a.result.status == FlightStatus::kReachedGoal);
}

TEST_CASE("the rotors' noise: N(0, sigma^2) on each rotor's speed per control period, seeded") {
  QuadParams vehicle;
  vehicle.motor_noise = 30.0;  // [rad/s]
  Simulation sim = RoomAt(Vec3(0, 0, 1));
  const double hover = vehicle.RotorSpeedFor(vehicle.HoverThrustPerRotor());
  const auto draws = [&](std::uint64_t seed, double thrust, int n) {
    MotorNoise noise(vehicle, seed);
    std::vector<double> speeds;
    for (int k = 0; k < n; ++k) {
      sim.SetRotorThrusts(Vec4::Constant(thrust));
      noise.Apply(&sim);
      for (int i = 0; i < kNumRotors; ++i) {
        speeds.push_back(vehicle.RotorSpeedFor(sim.RotorThrusts()[i]));
      }
    }
    return speeds;
  };
  const std::vector<double> a = draws(3, vehicle.HoverThrustPerRotor(), 1000);
  double sum = 0.0, squares = 0.0;
  for (double w : a) {
    sum += w - hover;
    squares += (w - hover) * (w - hover);
  }
  const double n = static_cast<double>(a.size());
  CHECK(std::abs(sum / n) < 4.0 * 30.0 / std::sqrt(n));  // unbiased, within 4 standard errors
  // the variance within the chi-square distribution's 0.01 % tails
  CHECK(squares / (30.0 * 30.0) > ChiSquareQuantile(n, -3.72));
  CHECK(squares / (30.0 * 30.0) < ChiSquareQuantile(n, 3.72));
  CHECK(draws(3, vehicle.HoverThrustPerRotor(), 10) ==
        std::vector<double>(a.begin(), a.begin() + 40));
  CHECK(draws(4, vehicle.HoverThrustPerRotor(), 10) !=
        std::vector<double>(a.begin(), a.begin() + 40));
  // at the rotor's top speed, the noise cannot pass it
  const double top = vehicle.RotorSpeedFor(vehicle.MaxRotorThrust());
  for (double w : draws(3, vehicle.MaxRotorThrust(), 50)) CHECK(w <= top + 1e-9);
  // none asked for, none added
  vehicle.motor_noise = 0.0;
  for (double w : draws(3, vehicle.HoverThrustPerRotor(), 5)) CHECK(w == doctest::Approx(hover));
}

TEST_CASE("a gust the controller cannot hold is a fly-away, not a success") {
  // 15 m/s of gust against a vehicle whose tilt limit holds about 7 m/s of drag
  const Vec3 hold(0, 0, 1.5);
  const Track track =
      FlyWith(FromFunction(6.0, [&](double) { return hold; }), hold, [](FlightLoop* loop) {
        Gust g;
        g.start = 1.0;
        g.rise = 0.5;
        g.duration = 4.0;
        g.peak = 15.0;
        loop->wind.gusts = {g};
        loop->aero = AeroParams{true, true};
      });
  CHECK(track.result.status == FlightStatus::kFlyAway);
}

}  // namespace aerobox
