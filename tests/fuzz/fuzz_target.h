// Shared by the libFuzzer targets: parse the input with one reader; InputError is the expected
// answer to bad input, anything else (a crash, a sanitizer report, another exception) is a
// finding. A map that does load must be sound.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include "common/error.h"
#include "map/map.h"

namespace aerobox::fuzz {

inline void Require(bool condition) {
  if (!condition) std::abort();
}

inline void CheckSound(const Map& map) {
  Require(map.bounds.min.allFinite() && map.bounds.max.allFinite());
  Require((map.bounds.min.array() <= map.bounds.max.array()).all());
  for (const Box& box : map.boxes) {
    Require(box.extent.min.allFinite() && box.extent.max.allFinite());
    Require((box.extent.min.array() <= box.extent.max.array()).all());
    Require((box.rgb.array() >= 0).all() && (box.rgb.array() <= 1).all());
  }
}

template <typename Parse>
int Run(const std::uint8_t* data, std::size_t size, Parse parse) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    parse(in);
  } catch (const InputError&) {
  }
  return 0;
}

}  // namespace aerobox::fuzz
