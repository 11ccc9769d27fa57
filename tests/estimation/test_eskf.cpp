// The error-state Kalman filter: late measurements, convergence at rest, the sensor suite's
// rules.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "estimation/eskf.h"
#include "estimation/sensing.h"

namespace aerobox {
namespace {

Mat15 Spread() {
  Vec15 sigma;
  sigma << Vec3::Constant(0.01), Vec3::Constant(0.02), Vec3::Constant(0.02), Vec3::Constant(0.2),
      Vec3::Constant(0.02);
  return sigma.cwiseAbs2().asDiagonal();
}

// Readings of a still IMU every millisecond.
std::vector<ImuSample> StillReadings(const ImuParams& p, int n, Imu* imu) {
  std::vector<ImuSample> out;
  const State still;
  for (int i = 0; i < n; ++i) {
    imu->Accumulate(0.001, still, Vec3::Zero(), Vec3::Zero());
    out.push_back(imu->Read((i + 1) * 0.001));
  }
  (void)p;
  return out;
}

TEST_CASE("a late measurement gives what it would have given on time") {
  ImuParams imu_params;
  imu_params.enabled = true;
  Imu imu(imu_params, 3);
  const std::vector<ImuSample> readings = StillReadings(imu_params, 200, &imu);
  PositionSensorParams mocap;
  mocap.enabled = true;
  PositionSensor sensor(mocap, 4);
  const PoseMeasurement m = sensor.Measure(0.100, State());

  ErrorStateKalmanFilter on_time(imu_params, mocap, NavState(), Spread(), 0.0, 0.5, 0.001);
  ErrorStateKalmanFilter late(imu_params, mocap, NavState(), Spread(), 0.0, 0.5, 0.001);
  for (const ImuSample& s : readings) {
    on_time.Propagate(s);
    if (std::abs(s.t - m.t) < 1e-9) on_time.Update(m);
    late.Propagate(s);
    if (std::abs(s.t - (m.t + 0.030)) < 1e-9) CHECK(late.Update(m));  // 30 ms late
  }
  CHECK((on_time.nominal().p_W - late.nominal().p_W).norm() < 1e-12);
  CHECK((on_time.nominal().v_W - late.nominal().v_W).norm() < 1e-12);
  CHECK((on_time.covariance() - late.covariance()).norm() < 1e-12);
  // a measurement older than the history is dropped
  PoseMeasurement old = m;
  old.t = -1.0;
  CHECK_FALSE(late.Update(old));
}

TEST_CASE("at rest with motion capture the filter finds the biases and stays consistent") {
  ImuParams imu_params;
  imu_params.enabled = true;
  Imu imu(imu_params, 8);
  PositionSensorParams mocap;
  mocap.enabled = true;
  PositionSensor sensor(mocap, 9);
  Mat15 P0 = Spread();
  P0.block<3, 3>(9, 9).diagonal().setConstant(std::pow(imu_params.accel_turn_on_bias, 2));
  P0.block<3, 3>(12, 12).diagonal().setConstant(std::pow(imu_params.gyro_turn_on_bias, 2));
  ErrorStateKalmanFilter filter(imu_params, mocap, NavState(), P0, 0.0, 0.5, 0.001);
  const State still;
  for (int i = 0; i < 20000; ++i) {  // 20 s
    imu.Accumulate(0.001, still, Vec3::Zero(), Vec3::Zero());
    filter.Propagate(imu.Read((i + 1) * 0.001));
    if ((i + 1) % 10 == 0) filter.Update(sensor.Measure((i + 1) * 0.001, still));
  }
  NavState truth;
  truth.accel_bias = imu.accel_bias();
  truth.gyro_bias = imu.gyro_bias();
  const Vec15 e = ErrorBetween(truth, filter.nominal());
  const Vec15 sigma = filter.covariance().diagonal().cwiseSqrt();
  for (int k = 0; k < 15; ++k) {
    CAPTURE(k);
    CHECK(std::abs(e[k]) < 4 * sigma[k]);
  }
  // the gyroscope's bias is found to a small fraction of its 1 deg/s spread
  CHECK((truth.gyro_bias - filter.nominal().gyro_bias).norm() < 0.1 * 0.0175);
}

TEST_CASE("the sensor suite needs both sensors and rates that divide the physics") {
  SensorParams p;
  p.imu.enabled = true;
  CHECK_THROWS_WITH_AS(p.Validate(0.001), doctest::Contains("sensors.position"),
                       std::invalid_argument);
  p.position.enabled = true;
  CHECK_NOTHROW(p.Validate(0.001));
  p.imu.rate = 300;
  CHECK_THROWS_WITH_AS(p.Validate(0.001), doctest::Contains("sensors.imu.rate"),
                       std::invalid_argument);
}

}  // namespace
}  // namespace aerobox
