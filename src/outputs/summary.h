// summary.json of a run: what the mission set up, planned and flew, in the keys the README
// lists (units in the key names). Written by `aerobox fly` and by the Python package.
#pragma once

#include <string>

#include "mission/mission.h"
#include "telemetry/json_object.h"

namespace aerobox {

// What the outputs made besides the flight.
struct OutputCounts {
  int telemetry_every = 1;  // one telemetry row per this many control steps
  int video_frames = 0;
  int video_fps = 30;  // [frames/s]
};

// "" when the flight followed its trajectory; otherwise why its numbers mean little (it was
// farther than kLargeTrackingError from its setpoint).
std::string TrackingNote(const FlightSetup& setup, const FlightResult& flight);

// Every key down to what the run reached (a run without a path has no trajectory keys), and the
// versions of aerobox and MuJoCo.
JsonObject RunSummary(const FlightSetup& setup, const MissionResult& result,
                      const OutputCounts& counts);

// A flight's own numbers, in the keys RunSummary gives them: distance, speeds, rotor effort,
// tracking, take-off, clearance, collision, MuJoCo's warning, control rate (a swarm's summary
// gives each vehicle's so).
void AddFlightNumbers(const FlightResult& flight, JsonObject* summary);

// [m] from the setpoint at worst: beyond it a flight is reported as not following its trajectory
// (the scenario tests' bound is 0.15 m)
inline constexpr double kLargeTrackingError = 0.25;

}  // namespace aerobox
