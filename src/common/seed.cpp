#include "common/seed.h"

namespace aerobox {
namespace {

std::uint64_t SplitMix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

}  // namespace

std::uint64_t StreamSeed(std::uint64_t seed, SeedStream stream) {
  return SplitMix64(SplitMix64(seed) ^ static_cast<std::uint64_t>(stream));
}

}  // namespace aerobox
