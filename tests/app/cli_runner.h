// Runs the aerobox command in-process (RunCli) with its words, for the app and scenario tests.
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "app/cli.h"

namespace aerobox::testing {

struct CliRun {
  int code = -1;
  std::string out;  // standard output
  std::string err;  // standard error
};

// `args` without the program name, e.g. {"fly", "scene.toml", "--no-video"}.
inline CliRun RunAerobox(const std::vector<std::string>& args) {
  std::vector<const char*> argv = {"aerobox"};
  for (const std::string& arg : args) argv.push_back(arg.c_str());
  std::ostringstream out, err;
  CliRun run;
  run.code = RunCli(static_cast<int>(argv.size()), argv.data(), out, err);
  run.out = out.str();
  run.err = err.str();
  return run;
}

}  // namespace aerobox::testing
