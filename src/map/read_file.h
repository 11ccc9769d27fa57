// Input files (maps, scenarios, start/goal files) are read here, and only here: the parsers
// below take streams.
#pragma once

#include <string>

namespace aerobox {

// The whole file; throws InputError naming the file when it cannot be opened or read.
std::string ReadTextFile(const std::string& path);

}  // namespace aerobox
