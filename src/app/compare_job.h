// `aerobox compare`: the trajectory generators our users know (trajectory/baselines.h) beside
// minimum snap, on the same waypoints and segment times, each flown in MuJoCo; one table.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace aerobox {

// Flies every generator on every scenario and prints a markdown table; writes, per scenario,
// <out_dir>/<name>_profiles.csv (t, method, x, y, z, ax, ay, az every 0.02 s) for
// tools/plot_compare.py. Returns the exit code (0, or 2 for bad input via InputError).
int RunCompare(const std::vector<std::string>& scenarios, const std::string& out_dir,
               std::ostream& out, std::ostream& progress);

}  // namespace aerobox
