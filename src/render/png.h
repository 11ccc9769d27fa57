// PNG encoding and decoding in memory (libpng stays in the .cpp; writing files is the caller's).
#pragma once

#include <string>
#include <string_view>

#include "render/image.h"

namespace aerobox {

// The image as PNG bytes (8-bit RGB). Throws std::runtime_error if libpng fails.
std::string EncodePng(const Image& image);

// Decodes 8-bit RGB or RGBA PNG bytes (alpha dropped); false for anything else or corrupt data.
bool DecodePng(std::string_view bytes, Image* image);

}  // namespace aerobox
