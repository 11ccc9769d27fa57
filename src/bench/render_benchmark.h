// Frames per second of the whole video path (render, read back, encode H.264 on the worker
// thread) against bare render + read back with the same settings, in one run.
#pragma once

#include <ostream>
#include <string>

namespace aerobox {

void CompareVideoPath(const std::string& scenario, std::ostream& out, std::ostream& progress);

}  // namespace aerobox
