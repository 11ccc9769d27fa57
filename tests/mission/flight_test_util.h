// Flights for the controller tests: an empty room, references from functions, and the circle
// and figure-8 of the README's tracking table.
#pragma once

#include <cmath>
#include <functional>
#include <vector>

#include "mission/flight.h"
#include "mission/reference_curves.h"

namespace aerobox::testing {

// A flight's result and its telemetry, one sample per control step.
struct Track {
  FlightResult result;
  std::vector<TelemetrySample> samples;
};

// The references of mission/reference_curves.h, under the names the tests use.
using aerobox::Circle;
using aerobox::CircleDuration;
using aerobox::Eight;
using aerobox::EightDuration;
using aerobox::EightRate;
using aerobox::FromFunction;
using aerobox::RampedPhase;
using aerobox::RoomAt;

}  // namespace aerobox::testing
