// MuJoCo's global error and warning hooks. The library's defaults print and wait for Enter
// (errors) or only print (warnings); ours never block and make warnings visible to callers.
#pragma once

#include <string>
#include <vector>

namespace aerobox {

// Installs the hooks once per process (thread-safe; later calls do nothing).
//  - a MuJoCo error is a bug or memory exhaustion inside the engine: the message goes to stderr
//    and the process exits with code 1 (MuJoCo cannot continue after one, and C++ exceptions
//    must not unwind through its C frames);
//  - warnings are collected for TakeMujocoWarnings() and counted.
void InstallMujocoMessageHandlers();

// The warnings raised since the last call, oldest first; clears the list.
std::vector<std::string> TakeMujocoWarnings();

}  // namespace aerobox
