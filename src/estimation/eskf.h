// An error-state Kalman filter (Solà 2017, "Quaternion kinematics for the error-state Kalman
// filter"): the IMU propagates a nominal state (position, velocity, attitude, accelerometer and
// gyroscope biases), position (and attitude) measurements correct it through a 15-dimensional
// error state with the attitude error in the body frame. A measurement that arrives late is
// applied at the time it was taken: the filter goes back to its state then and propagates the
// IMU readings since again.
#pragma once

#include <deque>

#include "common/state.h"
#include "common/types.h"
#include "estimation/sensors.h"

namespace aerobox {

using Vec15 = Eigen::Matrix<double, 15, 1>;
using Mat15 = Eigen::Matrix<double, 15, 15>;

struct NavState {
  Vec3 p_W = Vec3::Zero();
  Vec3 v_W = Vec3::Zero();
  Quat q_WB = Quat::Identity();
  Vec3 accel_bias = Vec3::Zero();  // [m/s^2]
  Vec3 gyro_bias = Vec3::Zero();   // [rad/s]
};

// The error of `estimate` against `truth` in the filter's coordinates: position, velocity,
// attitude (body frame rotation vector from the estimate to the truth), the two biases.
Vec15 ErrorBetween(const NavState& truth, const NavState& estimate);

class ErrorStateKalmanFilter {
 public:
  // The IMU's noise model, the measurement noise of the position sensor, the initial state and
  // covariance; `history` [s] is how late a measurement may arrive. `world_step` [s]: the step
  // of the world the IMU moves in when it integrates positions with each step's final velocity
  // (semi-implicit Euler, as MuJoCo does), which over an interval dt of constant acceleration a
  // advances them by v dt + a dt^2 (1 + world_step / dt) / 2 rather than v dt + a dt^2 / 2;
  // 0 for the continuous world.
  ErrorStateKalmanFilter(const ImuParams& imu, const PositionSensorParams& position,
                         const NavState& initial, const Mat15& covariance, double t, double history,
                         double world_step = 0.0);

  // Propagates from the last reading's end to this one's with this reading (it covers that
  // interval).
  void Propagate(const ImuSample& sample);
  // Corrects with a measurement taken at m.t (<= now); a measurement older than the history
  // is dropped (returns false).
  bool Update(const PoseMeasurement& m);

  const NavState& nominal() const { return nominal_; }
  const Mat15& covariance() const { return covariance_; }
  double time() const { return time_; }

 private:
  struct Entry {  // the filter after propagating to `t`, and the reading that brought it there
    double t;
    NavState nominal;
    Mat15 covariance;
    ImuSample sample;
  };
  void Advance(const ImuSample& sample);
  void Correct(const PoseMeasurement& m);

  ImuParams imu_;
  PositionSensorParams position_;
  double history_;
  double world_step_;
  NavState nominal_;
  Mat15 covariance_;
  double time_;
  std::deque<Entry> entries_;
};

}  // namespace aerobox
