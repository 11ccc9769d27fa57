// Sensors on the vehicle, seeded: an IMU (gyroscope and accelerometer with white noise, bias
// random walk and a turn-on bias) and a position sensor (motion capture with attitude, or a
// GPS-like receiver), each at its own rate, the latter with a latency.
#pragma once

#include <cstdint>
#include <optional>
#include <random>

#include "common/schema.h"
#include "common/state.h"
#include "common/types.h"

namespace aerobox {

// Defaults: the Bosch BMI088 that small quads carry (datasheet BST-BMI088-DS001): gyroscope
// noise density 0.014 deg/s/sqrt(Hz), zero-rate offset +-1 deg/s; accelerometer noise density
// 175 ug/sqrt(Hz), zero-g offset +-20 mg. The datasheet gives no bias instability; the random
// walks are typical of MEMS parts of this class (an estimate).
struct ImuParams {
  bool enabled = false;
  double rate = 1000.0;                  // [Hz]; divides the physics rate
  double gyro_noise_density = 2.44e-4;   // [rad/s/sqrt(Hz)] 0.014 deg/s/sqrt(Hz)
  double accel_noise_density = 1.72e-3;  // [m/s^2/sqrt(Hz)] 175 ug/sqrt(Hz)
  double gyro_bias_walk = 2e-5;          // [rad/s^2/sqrt(Hz)]
  double accel_bias_walk = 3e-4;         // [m/s^3/sqrt(Hz)]
  double gyro_turn_on_bias = 0.0175;     // [rad/s] 1 sigma per axis: 1 deg/s
  double accel_turn_on_bias = 0.196;     // [m/s^2] 1 sigma per axis: 20 mg

  void Describe(Archive& a);  // [sensors.imu] (common/schema.h)
  void Validate() const;      // throws std::invalid_argument naming the field
};

// One reading: the mean angular velocity and specific force over the interval that ends at t,
// in the body frame, as an averaging MEMS IMU outputs them.
struct ImuSample {
  double t = 0.0;               // [s]
  double interval = 0.0;        // [s] the interval it covers
  Vec3 gyro_B = Vec3::Zero();   // [rad/s]
  Vec3 accel_B = Vec3::Zero();  // [m/s^2] specific force (reads +g upwards at rest)
};

class Imu {
 public:
  Imu(const ImuParams& params, std::uint64_t seed);
  // Adds one physics step of `step` [s] that started in `before` and ended with angular
  // velocity `after_w_B`, under the world acceleration a_W [m/s^2].
  void Accumulate(double step, const State& before, const Vec3& after_w_B, const Vec3& a_W);
  // Ends the interval at t: the reading, with noise and bias; resets the accumulation.
  ImuSample Read(double t);
  Vec3 gyro_bias() const { return gyro_bias_; }
  Vec3 accel_bias() const { return accel_bias_; }

 private:
  ImuParams params_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  Vec3 gyro_bias_, accel_bias_;
  Vec3 rotation_ = Vec3::Zero();  // sum of w dt [rad]
  Vec3 velocity_ = Vec3::Zero();  // sum of specific force dt [m/s]
  double interval_ = 0.0;         // [s]
  Vec3 Noise(double sigma);
};

enum class PositionSensorKind { kMocap, kGps };

struct PositionSensorParams {
  bool enabled = false;
  PositionSensorKind kind = PositionSensorKind::kMocap;
  // Motion capture (Vicon / OptiTrack class): sub-millimetre noise, 100 Hz as tracked
  // quadrotor labs stream it, 10 ms from the camera to the vehicle; it tracks attitude too.
  double rate = 100.0;                // [Hz]; divides the physics rate
  Vec3 noise = Vec3::Constant(1e-3);  // [m] 1 sigma per world axis
  double latency = 0.010;             // [s]
  double attitude_noise = 0.005;      // [rad] 1 sigma per body axis; 0: no attitude

  // A GPS-like receiver: 10 Hz, 0.5 m horizontal and 1 m vertical (RTK-less consumer
  // receivers do worse over minutes; this is their short-term noise), 100 ms, no attitude.
  static PositionSensorParams Gps();
  void Describe(Archive& a);  // [sensors.position] (common/schema.h); `enabled` is the table's
  void Validate() const;      // throws std::invalid_argument naming the field
};

struct PoseMeasurement {
  double t = 0.0;            // [s] when it was taken (it arrives latency later)
  Vec3 p_W = Vec3::Zero();   // [m]
  std::optional<Quat> q_WB;  // motion capture only
};

class PositionSensor {
 public:
  PositionSensor(const PositionSensorParams& params, std::uint64_t seed);
  PoseMeasurement Measure(double t, const State& truth);

 private:
  PositionSensorParams params_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

// exp and log of rotation vectors [rad] (SO(3)), for the sensors and the filter.
Quat RotationVectorToQuat(const Vec3& phi);
Vec3 QuatToRotationVector(const Quat& q);

}  // namespace aerobox
