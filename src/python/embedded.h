// User Python classes in an ordinary `aerobox fly` run (--controller, --trajectory-module,
// --planner-module file.py:Class): the command embeds Debian's Python, imports the files and
// enters each class in its seam's registry under its spec. No pybind11 types here.
#pragma once

#include <string>

#include "mission/setup.h"

namespace aerobox {

struct PythonModules {
  std::string controller;  // "file.py:Class": Class(quad_params).update(t, state, flat) -> dict
  std::string trajectory;  // Class(path) (or flightsim's Class(world, start, goal)); update(t)
  std::string planner;     // Class().plan(world, start, goal) -> (N, 3) array
  std::string command = "auto";  // which command keys fly (python/seams.h: CommandChoice)
  bool any() const { return !controller.empty() || !trajectory.empty() || !planner.empty(); }
};

// Starts the interpreter (once), imports each given class, registers it under its spec and
// points the set-up at it. Throws InputError naming the option, for a file that does not import
// or a class that is not there. Later, an exception in a planner's or a trajectory's code
// leaves the run as an InputError naming the option; a controller's (or a command with a wrong
// key, shape or a non-finite value) ends the flight as FlightStatus::kControllerFailed, its
// message naming the time and the key, its detail the traceback (python/seams.h).
void UsePythonModules(const PythonModules& modules, FlightSetup* setup);

}  // namespace aerobox
