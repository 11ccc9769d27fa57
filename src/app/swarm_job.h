// `aerobox fly` of a scenario with [[vehicles]]: several vehicles in one world (RunSwarm), each
// vehicle's files in a folder of its own, the world's video and one summary for all.
#pragma once

#include <ostream>

#include "app/fly_job.h"
#include "outputs/files.h"

namespace aerobox {

// Flies the set-up's vehicles and writes into `output`'s staging folder: <vehicle>/path.csv,
// trajectory.csv and telemetry.csv per vehicle (each in the one telemetry schema a lone flight
// writes, so every tool that reads a flight's files reads each vehicle's), video.mp4 and
// overview.png of the world, summary.json with an entry per vehicle. Returns the exit code: 0
// when every vehicle reached its goal.
int FlySwarmInto(const OutputFolder& output, const FlightSetup& setup, const FlyOptions& options,
                 std::ostream& out, std::ostream& err);

}  // namespace aerobox
