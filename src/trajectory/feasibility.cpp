#include "trajectory/feasibility.h"

#include <algorithm>
#include <cmath>

#include "common/stop.h"

namespace aerobox {
namespace {

// Body rates at constant yaw from acceleration and jerk (Mellinger and Kumar 2011, eq. 7):
// the thrust axis z_b turns with the part of the jerk across it.
Vec3 BodyRates(const Vec3& a, const Vec3& j, double yaw, Vec3* z_b) {
  const Vec3 thrust = a + Vec3(0, 0, kGravity);
  const double norm = thrust.norm();
  *z_b = thrust / norm;
  const Vec3 x_c(std::cos(yaw), std::sin(yaw), 0.0);
  Vec3 y_b = z_b->cross(x_c);
  if (y_b.norm() < 1e-9) y_b = Vec3::UnitY();
  y_b.normalize();
  const Vec3 x_b = y_b.cross(*z_b);
  const Vec3 h = (j - z_b->dot(j) * *z_b) / norm;
  return Vec3(-h.dot(y_b), h.dot(x_b), 0.0);
}

struct Worst {
  FeasibilityCheck check;
  void Consider(double ratio, int order, double t, const std::string& limit) {
    const double scale = ratio > 0 ? std::pow(ratio, 1.0 / order) : 0.0;
    if (scale > check.scale) check = {ratio, scale, t, limit};
  }
};

// `to_rotors`: the inverse of limits.allocation, factorised once per check.
// The acceleration and jerk the thrust must produce at t: the trajectory's, less drag's share.
void ThrustOutputs(const PiecewiseTrajectory& trajectory, const FlatnessLimits& limits, double t,
                   Vec3* a, Vec3* j) {
  FlatOutput f;
  f.v_W = trajectory.Evaluate3(t, kVelocity);
  f.a_W = trajectory.Evaluate3(t, kAcceleration);
  f.j_W = trajectory.Evaluate3(t, kJerk);
  f = CompensateDrag(f, limits.drag, limits.wind);
  *a = f.a_W;
  *j = f.j_W;
}

void CheckAt(const PiecewiseTrajectory& trajectory, const FlatnessLimits& limits,
             const Mat4& to_rotors, double t, Worst* worst) {
  const Vec3 v = trajectory.Evaluate3(t, kVelocity);
  const Vec3 a_path = trajectory.Evaluate3(t, kAcceleration);
  Vec3 a, j;
  ThrustOutputs(trajectory, limits, t, &a, &j);
  worst->Consider(v.norm() / limits.max_speed, 1, t, "speed");
  worst->Consider(std::abs(v.z()) / limits.max_vertical_speed, 1, t, "vertical speed");
  if (std::isfinite(limits.max_accel)) {
    worst->Consider(a_path.norm() / limits.max_accel, 2, t, "acceleration");
  }
  const Vec3 thrust = a + Vec3(0, 0, kGravity);
  if (thrust.z() <= 1e-3 * kGravity) {
    // falling at gravity or faster: the rotors cannot pull down; the ratio of the downward
    // acceleration to gravity scales with time squared as the others do
    worst->Consider(std::max(1.0, -a.z() / (0.999 * kGravity)) * 1.001, 2, t, "thrust direction");
    return;
  }
  const double tan_tilt = thrust.head<2>().norm() / thrust.z();
  worst->Consider(tan_tilt / std::tan(limits.max_tilt), 2, t, "tilt");

  Vec3 z_b;
  const Vec3 w = BodyRates(a, j, limits.yaw, &z_b);
  worst->Consider(w.norm() / limits.max_rate, 1, t, "body rate");
  // angular acceleration by a central difference of the rates (the snap's effect)
  constexpr double h = 1e-4;
  Vec3 unused;
  const double t_minus = std::max(0.0, t - h);
  const double t_plus = std::min(trajectory.duration(), t + h);
  Vec3 a_minus, j_minus, a_plus, j_plus;
  ThrustOutputs(trajectory, limits, t_minus, &a_minus, &j_minus);
  ThrustOutputs(trajectory, limits, t_plus, &a_plus, &j_plus);
  const Vec3 w_minus = BodyRates(a_minus, j_minus, limits.yaw, &unused);
  const Vec3 w_plus = BodyRates(a_plus, j_plus, limits.yaw, &unused);
  const Vec3 alpha =
      t_plus > t_minus ? Vec3((w_plus - w_minus) / (t_plus - t_minus)) : Vec3::Zero();
  const Vec3 j_w = limits.inertia.cwiseProduct(w);
  const Vec3 moment = limits.inertia.cwiseProduct(alpha) + w.cross(j_w);
  Eigen::Vector4d wrench;
  wrench << limits.mass * thrust.norm(), moment;
  const Eigen::Vector4d rotors = to_rotors * wrench;
  // the rotors swing about their share of the weight: that swing scales with time squared
  const double hover = limits.mass * kGravity / 4.0;
  for (int i = 0; i < 4; ++i) {
    const std::string name = "rotor " + std::to_string(i + 1) + " thrust";
    if (rotors[i] >= hover) {
      worst->Consider((rotors[i] - hover) / (limits.max_rotor_thrust - hover), 2, t, name);
    } else {
      worst->Consider((hover - rotors[i]) / (hover - limits.min_rotor_thrust), 2, t, name);
    }
  }
}

}  // namespace

FeasibilityCheck CheckFeasibility(const PiecewiseTrajectory& trajectory,
                                  const FlatnessLimits& limits, double dt, double t0, double t1) {
  Worst worst;
  if (trajectory.empty()) return worst.check;
  t1 = std::min(t1, trajectory.duration());
  // every dt, and at most kMaxSamples in the interval
  constexpr int kMaxSamples = 400;
  const int steps = std::clamp(static_cast<int>(std::ceil((t1 - t0) / dt)), 1, kMaxSamples);
  const Mat4 to_rotors = limits.allocation.inverse();
  for (int i = 0; i <= steps; ++i) {
    // the time searches check whole trajectories, hundreds of times: a point to stop at
    if (i % 50 == 0) ThrowIfStopRequested("checking the trajectory's feasibility");
    CheckAt(trajectory, limits, to_rotors, t0 + (t1 - t0) * i / steps, &worst);
  }
  return worst.check;
}

std::vector<FeasibilityCheck> CheckSegments(const PiecewiseTrajectory& trajectory,
                                            const FlatnessLimits& limits, double dt) {
  std::vector<FeasibilityCheck> checks;
  const std::vector<double> knots = trajectory.KnotTimes();
  for (size_t i = 0; i + 1 < knots.size(); ++i) {
    // long trajectories: hundreds of segments, each sampled (Ctrl-C stops between them)
    ThrowIfStopRequested("checking the trajectory's feasibility");
    checks.push_back(CheckFeasibility(trajectory, limits, dt, knots[i], knots[i + 1]));
  }
  return checks;
}

}  // namespace aerobox
