// The one way aerobox runs another program (a sweep's runs, aerobox-bench, the benchmarks' Python
// and sweeps): posix_spawn, no shell, no signal blocked in the child, and Ctrl-C passed on.
#pragma once

#include <sys/types.h>

#include <functional>
#include <string>
#include <vector>

namespace aerobox {

struct ProcessSpec {
  std::vector<std::string> argv;         // argv[0] is a path (no search of PATH)
  std::vector<std::string> environment;  // NAME=VALUE, added to (or replacing) this process's
  std::string output;                    // standard output to this file (truncated); "": ours
  bool error_to_output = false;          // standard error to the same place as the output
  bool null_input = false;               // standard input from /dev/null
};

// Starts the process. `output_pipe`: when given, its standard output goes to a pipe whose
// reading end is returned there (the caller reads and closes it). Throws std::runtime_error
// naming the program when it cannot start.
pid_t StartProcess(const ProcessSpec& spec, int* output_pipe = nullptr);

// A waitpid status as a shell reports it: the exit code, or 128 + the signal that ended it.
int ExitCodeOf(int wait_status);

// Runs the process to its end and returns ExitCodeOf its status. A stop request (common/stop.h)
// is passed on to it as SIGINT, once; it is not thrown here: the caller sees the code
// (130 from an aerobox) and StopRequested(). `on_output`: its standard output, as it comes.
int RunProcess(const ProcessSpec& spec,
               const std::function<void(const std::string&)>& on_output = {});

}  // namespace aerobox
