// Independent random streams from one seed: every seeded part of a flight (turbulence, each
// sensor, the estimator's start) draws from its own stream, so turning one part on or off does
// not change what the others draw.
#pragma once

#include <cstdint>

namespace aerobox {

// Stream numbers, one per part; a new part takes a new number.
enum class SeedStream : std::uint64_t {
  kTurbulence = 1,
  kImu = 2,
  kPositionSensor = 3,
  kInitialEstimate = 4,
  kUnknownBoxes = 5,
  kMotorNoise = 6,
  kEnvironment = 7,  // a learning environment's random starts
  kDepthCamera = 8,  // the depth camera's noise and dropouts
};

// A seed for `stream` derived from `seed` (SplitMix64 over both: well mixed, and the same on
// every platform).
std::uint64_t StreamSeed(std::uint64_t seed, SeedStream stream);

}  // namespace aerobox
