// Flights that push back: every map over seeds, controllers and mean winds, with Dryden
// turbulence, drag, an IMU and motion capture, the controller flying on the estimate.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "common/progress.h"

namespace aerobox {

struct RobustnessParams {
  std::vector<std::string> scenarios;  // scenario.toml files
  // controller kinds, each alone or with "+observer" (the disturbance observer)
  std::vector<std::string> controllers = {"cascade", "se3", "indi", "cascade+observer",
                                          "se3+observer"};
  std::vector<double> winds = {0.0, 2.0, 4.0, 6.0};  // mean wind speeds [m/s]
  int seeds = 20;                                    // seeds 1..seeds per map, controller, wind
  std::string csv;                                   // one row per flight there ("": none)
};

// The controllers of a comma-separated `list`; throws std::invalid_argument for none, or naming
// one that is not "kind" or "kind+observer" of a registered kind (indi has no observer: it
// measures the force itself).
std::vector<std::string> RobustnessControllers(const std::string& list);
void ValidateRobustnessControllers(const std::vector<std::string>& controllers);

// Prints two Markdown tables: per map, controller and wind (a row as each ends), the success
// rate, tracking RMS median and worst, minimum clearance, estimate RMS median and the failures
// by seed; then per controller and wind, the flights that reached the goal over every map.
// Progress goes to `progress`.
void RobustnessTable(const RobustnessParams& params, std::ostream& out, ProgressDisplay& progress);

// A figure-8 (4 x 2 m, at up to 2 m/s, one loop) in a constant wind along x at each of
// `params.winds`, with drag, an IMU and motion capture: the mean position error of each of
// `params.controllers`, beside the errors Neural-Fly published (O'Connell et al., Science
// Robotics 2022) for their baseline, INDI and L1 adaptive controllers.
void WindEightTable(const RobustnessParams& params, std::ostream& out, ProgressDisplay& progress);

}  // namespace aerobox
