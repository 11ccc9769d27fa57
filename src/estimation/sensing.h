// The sensors and the estimator as one part of the flight loop: told about every physics step,
// it reads the IMU and the position sensor at their rates, delivers each measurement after its
// latency and keeps the filter's estimate, which the controller flies on.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>

#include "common/schema.h"
#include "common/state.h"
#include "estimation/eskf.h"
#include "estimation/sensors.h"

namespace aerobox {

// The filter's initial uncertainty (1 sigma); the biases start at zero with the IMU's turn-on
// spread. The initial estimate is the truth plus a draw from this spread.
struct EstimatorParams {
  double position_sigma = 0.01;  // [m]
  double velocity_sigma = 0.02;  // [m/s]
  double attitude_sigma = 0.02;  // [rad]
  double history = 0.5;          // [s] how late a measurement may arrive and still count

  void Describe(Archive& a);  // [sensors.estimator] (common/schema.h)
  void Validate() const;
};

struct SensorParams {
  ImuParams imu;
  PositionSensorParams position;
  EstimatorParams estimator;

  bool Enabled() const { return imu.enabled || position.enabled; }
  // Both sensors or neither (the filter needs the IMU to propagate and a position to stay
  // bounded), rates that divide the physics rate `step` [s]. Throws std::invalid_argument.
  void Validate(double step) const;
};

// What the sensors and the filter say at one moment, against the truth (for telemetry and
// consistency checks).
struct EstimateSample {
  State estimate;                       // what the controller flies on
  Vec15 error = Vec15::Zero();          // truth minus estimate (ErrorBetween)
  Vec15 sigma = Vec15::Zero();          // the filter's standard deviations
  double nees = 0.0;                    // normalised estimation error squared, e' P^-1 e
  ImuSample imu;                        // the latest reading
  std::optional<PoseMeasurement> pose;  // the latest measurement that arrived
};

class SensorSuite {
 public:
  // At time t [s] with the vehicle in `truth`; `step` [s] is the physics step.
  SensorSuite(const SensorParams& params, std::uint64_t seed, double step, double t,
              const State& truth);

  // After each physics step: the state it started from, the state now and the step's
  // acceleration [m/s^2].
  void AfterStep(double t, const State& before, const State& now, const Vec3& a_W);

  // What the controller sees: the filter's position, velocity and attitude, and the latest
  // gyroscope reading less the estimated bias.
  State Estimate() const;
  // The acceleration [m/s^2] (world, gravity not included) the latest accelerometer reading
  // gives: less the estimated bias, turned by the estimated attitude.
  Vec3 Acceleration_W() const;
  // The estimate against `truth`.
  EstimateSample Sample(const State& truth) const;
  // The truth in the filter's terms (with the IMU's current biases), for its errors.
  NavState TruthOf(const State& truth) const;
  const ErrorStateKalmanFilter& filter() const { return filter_; }
  const ImuSample& last_imu() const { return last_imu_; }
  const std::optional<PoseMeasurement>& last_pose() const { return last_pose_; }

 private:
  SensorParams params_;
  Imu imu_;
  PositionSensor position_;
  ErrorStateKalmanFilter filter_;
  double step_ = 0.0;  // [s] physics
  long steps_ = 0;
  int imu_divider_ = 1;
  int position_divider_ = 1;
  std::deque<PoseMeasurement> in_flight_;  // taken, not yet arrived
  ImuSample last_imu_;
  std::optional<PoseMeasurement> last_pose_;  // the latest that arrived
};

}  // namespace aerobox
