// Flights for the controller tests: an empty room, references from functions, and the circle
// and figure-8 of the README's tracking table.
#pragma once

#include <cmath>
#include <functional>
#include <vector>

#include "mission/flight.h"
#include "mission/reference_curves.h"
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

// The references of mission/reference_curves.h, under the names the tests use.
using aerobox::Circle;
using aerobox::CircleDuration;
using aerobox::Eight;
using aerobox::EightDuration;
using aerobox::EightRate;
using aerobox::FromFunction;
using aerobox::RampedPhase;

}  // namespace aerobox::testing
