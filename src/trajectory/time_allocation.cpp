#include "trajectory/time_allocation.h"

#include <algorithm>
#include <cmath>

namespace aerobox {

double TrapezoidTime(double length, double max_speed, double max_accel) {
  const double ramp = max_speed * max_speed / max_accel;  // distance to speed up and slow down
  if (length >= ramp) return length / max_speed + max_speed / max_accel;
  return 2.0 * std::sqrt(length / max_accel);
}

std::vector<double> TrapezoidDurations(const std::vector<Vec3>& waypoints, double max_speed,
                                       double max_accel) {
  std::vector<double> durations;
  for (size_t i = 1; i < waypoints.size(); ++i) {
    durations.push_back(
        TrapezoidTime((waypoints[i] - waypoints[i - 1]).norm(), max_speed, max_accel));
  }
  return durations;
}

double ScaleToLimits(double max_speed, double max_accel, double dt,
                     PiecewiseTrajectory* trajectory) {
  const double speed = trajectory->MaxNorm(kVelocity, dt);
  const double accel = trajectory->MaxNorm(kAcceleration, dt);
  const double factor = std::max(speed / max_speed, std::sqrt(accel / max_accel));
  if (factor > 0 && std::isfinite(factor)) trajectory->ScaleTime(factor);
  return factor;
}

}  // namespace aerobox
