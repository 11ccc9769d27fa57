#include "mission/reference_curves.h"

#include <cmath>
#include <utility>

#include "scene/scene_mjcf.h"

namespace aerobox {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The integral of a quintic smoothstep rising over `ramp` seconds.
double RampIntegral(double t, double ramp) {
  if (t <= 0) return 0;
  if (t >= ramp) return t - ramp / 2;
  const double s = t / ramp;
  return ramp * (2.5 * std::pow(s, 4) - 3 * std::pow(s, 5) + std::pow(s, 6));
}

}  // namespace

Reference FromFunction(double duration, std::function<Vec3(double)> position) {
  Reference reference;
  reference.duration = duration;
  reference.evaluate = [position = std::move(position)](double t, int derivative) -> Vec3 {
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

double RampedPhase(double t, double rate, double ramp, double duration) {
  return rate * (RampIntegral(t, ramp) - RampIntegral(t - (duration - ramp), ramp));
}

double CircleDuration() { return 2.0 + 2 * 2 * kPi; }

Vec3 Circle(double t) {
  const double phase = RampedPhase(t, 1.0, 2.0, CircleDuration());
  return Vec3(std::cos(phase) - 1.0, std::sin(phase), 1.5);
}

double EightRate() { return 2.0 / (2.0 * std::sqrt(2.0)); }

double EightDuration() { return 2.0 + 2 * kPi / EightRate(); }

Vec3 Eight(double t) {
  const double phase = RampedPhase(t, EightRate(), 2.0, EightDuration());
  return Vec3(2.0 * std::sin(phase), std::sin(2 * phase), 1.5);
}

Simulation RoomAt(const Vec3& start, const Map& extra, const QuadParams& vehicle) {
  Map map = extra;
  map.name = "room";
  map.bounds = {Vec3(-10, -10, 0), Vec3(10, 10, 6)};
  SceneOptions options;
  options.vehicle_position = start;
  Simulation sim = Simulation::FromXml(BuildSceneMjcf(map, vehicle, options), "room");
  sim.SetRotorThrusts(Vec4::Constant(vehicle.HoverThrustPerRotor()));
  return sim;
}

}  // namespace aerobox
