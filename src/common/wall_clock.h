// Wall-clock time for measuring costs (never for results, which follow simulation time): the
// seconds since an instant of the steady clock.
#pragma once

#include <chrono>

namespace aerobox {

using WallClock = std::chrono::steady_clock;

inline double Seconds(WallClock::time_point since) {
  return std::chrono::duration<double>(WallClock::now() - since).count();
}

}  // namespace aerobox
