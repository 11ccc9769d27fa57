// The aerobox command line: parses arguments, runs a command, maps outcomes to exit codes.
#pragma once

#include <ostream>

namespace aerobox {

// Runs `aerobox <argv...>` with results on `out` and messages on `err`; returns the exit code
// (app/exit_codes.h). Never throws.
int RunCli(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace aerobox
