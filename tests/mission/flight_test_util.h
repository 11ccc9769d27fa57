// Flights for the controller tests: an empty room, references from functions, and the circle
// and figure-8 of the README's tracking table.
#pragma once

#include <cmath>
#include <functional>
#include <vector>

#include "mission/flight.h"
#include "scene/scene_mjcf.h"

namespace aerobox::testing {

// A flight's result and its telemetry, one sample per control step.
struct Track {
  FlightResult result;
  std::vector<TelemetrySample> samples;
};

// An empty 20 x 20 x 6 m room with the vehicle at rest at `start` (rotors at hover thrust).
inline Simulation RoomAt(const Vec3& start, const Map& extra = Map(),
                         const QuadParams& vehicle = QuadParams()) {
  Map map = extra;
  map.name = "room";
  map.bounds = {Vec3(-10, -10, 0), Vec3(10, 10, 6)};
  SceneOptions options;
  options.vehicle_position = start;
  Simulation sim = Simulation::FromXml(BuildSceneMjcf(map, vehicle, options), "room");
  sim.SetRotorThrusts(Vec4::Constant(vehicle.HoverThrustPerRotor()));
  return sim;
}

// A reference from a position function, derivatives by central differences. The step grows
// with the order so that rounding (1e-16 m / h^order) stays below the truncation error
// (h^2 times a higher derivative): 1e-4 s for velocity and acceleration (about 1e-8 of the
// derivative), 1e-3 s for jerk and 1e-2 s for snap (about 1e-4 of it, far below what a
// controller notices).
inline Reference FromFunction(double duration, std::function<Vec3(double)> position) {
  Reference reference;
  reference.duration = duration;
  reference.evaluate = [position](double t, int derivative) -> Vec3 {
    const auto p = [&](double dt) { return position(t + dt); };
    if (derivative == kPosition) return position(t);
    if (derivative == kVelocity) return (p(1e-4) - p(-1e-4)) / 2e-4;
    if (derivative == kAcceleration) return (p(1e-4) - 2 * p(0) + p(-1e-4)) / 1e-8;
    if (derivative == kJerk) {
      constexpr double h = 1e-3;
      return (p(2 * h) - 2 * p(h) + 2 * p(-h) - p(-2 * h)) / (2 * h * h * h);
    }
    constexpr double h = 1e-2;
    return (p(2 * h) - 4 * p(h) + 6 * p(0) - 4 * p(-h) + p(-2 * h)) / (h * h * h * h);
  };
  return reference;
}

// Integral of a quintic smoothstep rising over `ramp` seconds.
inline double RampIntegral(double t, double ramp) {
  if (t <= 0) return 0;
  if (t >= ramp) return t - ramp / 2;
  const double s = t / ramp;
  return ramp * (2.5 * std::pow(s, 4) - 3 * std::pow(s, 5) + std::pow(s, 6));
}

// Phase whose rate rises from 0 to `rate` over `ramp` seconds and falls back to 0 over the last
// `ramp` seconds before `duration`: periodic references start and end at rest.
inline double RampedPhase(double t, double rate, double ramp, double duration) {
  return rate * (RampIntegral(t, ramp) - RampIntegral(t - (duration - ramp), ramp));
}

// Two laps of a 1 m circle at 1 m/s (1 rad/s), with 2 s ramps at both ends, at 1.5 m.
inline double CircleDuration() { return 2.0 + 2 * 2 * M_PI; }
inline Vec3 Circle(double t) {
  const double phase = RampedPhase(t, 1.0, 2.0, CircleDuration());
  return Vec3(std::cos(phase) - 1.0, std::sin(phase), 1.5);
}

// One loop of a figure-8, x = A sin(w t), y = A/2 sin(2 w t), at up to 2 m/s (A = 2 m).
inline double EightRate() { return 2.0 / (2.0 * std::sqrt(2.0)); }
inline double EightDuration() { return 2.0 + 2 * M_PI / EightRate(); }
inline Vec3 Eight(double t) {
  const double phase = RampedPhase(t, EightRate(), 2.0, EightDuration());
  return Vec3(2.0 * std::sin(phase), std::sin(2 * phase), 1.5);
}

}  // namespace aerobox::testing
