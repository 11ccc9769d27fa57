// An RGB image, rows top-down, 3 bytes a pixel.
#pragma once

#include <cstdint>
#include <vector>

namespace aerobox {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  // width * height * 3

  std::uint8_t* Pixel(int x, int y) { return &rgb[3 * (static_cast<size_t>(y) * width + x)]; }
  const std::uint8_t* Pixel(int x, int y) const {
    return &rgb[3 * (static_cast<size_t>(y) * width + x)];
  }
};

}  // namespace aerobox
