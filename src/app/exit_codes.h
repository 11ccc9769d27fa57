// Process exit codes of the aerobox command (the contract in DESIGN.md).
#pragma once

#include "outputs/interrupt.h"

namespace aerobox {

enum ExitCode : int {
  kExitReachedGoal = 0,  // success (for commands other than fly: the command did its job)
  kExitUnexpected = 1,   // anything unexpected (a bug, out of memory, an engine error)
  kExitBadInput = 2,     // usage, map or scenario errors, unwritable output
  kExitNoPath = 3,
  kExitNoTrajectory = 4,
  kExitFlightFailed = 5,                    // collision, timeout, divergence
  kExitInterrupted = kInterruptedExitCode,  // Ctrl-C (the shell's convention: 128 + SIGINT)
};

}  // namespace aerobox
