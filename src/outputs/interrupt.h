// Ctrl-C. The flight stops at its next control step (a cooperative check, StopRequested());
// everything else (planning, Ipopt, a benchmark, a comparison) is stopped by a watchdog one
// second after the signal: it removes the temporary files of the outputs being written
// (PartialFiles) and ends the process with exit code 130. Either way only complete files are
// left.
#pragma once

#include <atomic>
#include <string>

namespace aerobox {

// What the watchdog ends the process with: the shell's code for an end by SIGINT (128 + 2).
inline constexpr int kInterruptedExitCode = 130;

// Installs the SIGINT handler and the watchdog thread (once; later calls do nothing).
void InstallInterruptHandler();

// Set once Ctrl-C was pressed.
const std::atomic<bool>& StopRequested();

// The temporary files being written now; the watchdog removes them before it ends the process.
// Thread-safe.
void RegisterPartialFile(const std::string& path);
void UnregisterPartialFile(const std::string& path);

}  // namespace aerobox
