// Ctrl-C. The handler sets the one stop flag (common/stop.h); every long loop checks it and the
// command leaves by itself within milliseconds, exit code 130, its temporary files removed by
// the destructors that own them. A watchdog is the last resort: if the process is still
// running kGrace after the signal, some work did not check the flag (a bug to report); it says
// so, removes the temporary files and folders being written (common/stop.h) and ends the
// process with exit code 130. Either way only complete files are left.
#pragma once

#include <chrono>

#include "common/stop.h"

namespace aerobox {

// How long the watchdog lets the cooperative stop take before it ends the process.
inline constexpr std::chrono::milliseconds kInterruptGrace{2000};

// Installs the SIGINT handler and the watchdog thread (once; later calls do nothing).
void InstallInterruptHandler();

}  // namespace aerobox
