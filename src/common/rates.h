// Parts of the flight loop that run every few physics steps (the controller, the sensors).
#pragma once

#include <string>

namespace aerobox {

// How many physics steps of `step` [s] make one period at `rate` [Hz]; throws
// std::invalid_argument ("<what> <rate> Hz must divide the physics rate ...") unless it is a
// whole number of at least one.
int StepsPerPeriod(double rate, double step, const std::string& what);

}  // namespace aerobox
