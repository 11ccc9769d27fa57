#include "estimation/sensors.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace aerobox {
Quat RotationVectorToQuat(const Vec3& phi) {
  const double angle = phi.norm();
  if (angle < 1e-12) return Quat(1.0, 0.5 * phi.x(), 0.5 * phi.y(), 0.5 * phi.z()).normalized();
  return Quat(Eigen::AngleAxisd(angle, phi / angle));
}

Vec3 QuatToRotationVector(const Quat& q) {
  Quat u = q.normalized();
  if (u.w() < 0) u.coeffs() = -u.coeffs();  // the shorter way round
  const double s = u.vec().norm();
  if (s < 1e-12) return 2.0 * u.vec();
  return 2.0 * std::atan2(s, u.w()) * u.vec() / s;
}

void ImuParams::Describe(Archive& a) {
  a.Number({"rate", "Hz", "readings per second (divides the physics rate)"}, &rate, 1, 1000);
  a.Number({"gyro_noise_density", "rad/s/sqrt(Hz)", "the gyro's white noise"}, &gyro_noise_density,
           0, 100);
  a.Number({"accel_noise_density", "m/s^2/sqrt(Hz)", "the accelerometer's white noise"},
           &accel_noise_density, 0, 100);
  a.Number({"gyro_bias_walk", "rad/s^2/sqrt(Hz)", "the gyro bias's random walk"}, &gyro_bias_walk,
           0, 100);
  a.Number({"accel_bias_walk", "m/s^3/sqrt(Hz)", "the accelerometer bias's random walk"},
           &accel_bias_walk, 0, 100);
  a.Number({"gyro_turn_on_bias", "rad/s", "the gyro's bias at power-on, 1 sigma per axis"},
           &gyro_turn_on_bias, 0, 100);
  a.Number({"accel_turn_on_bias", "m/s^2", "the accelerometer's bias at power-on, 1 sigma"},
           &accel_turn_on_bias, 0, 100);
}

void ImuParams::Validate() const { ValidateFields(*this, "imu"); }

Imu::Imu(const ImuParams& params, std::uint64_t seed) : params_(params), rng_(seed) {
  params_.Validate();
  gyro_bias_ = Noise(params_.gyro_turn_on_bias);
  accel_bias_ = Noise(params_.accel_turn_on_bias);
}

Vec3 Imu::Noise(double sigma) { return sigma * Vec3(normal_(rng_), normal_(rng_), normal_(rng_)); }

void Imu::Accumulate(double step, const State& before, const Vec3& after_w_B, const Vec3& a_W) {
  // MuJoCo's semi-implicit Euler: the step's acceleration acts at its start's attitude, and the
  // attitude turns with the step's final angular velocity
  const Vec3 specific_W = a_W + Vec3(0, 0, kGravity);
  velocity_ += before.q_WB.conjugate() * specific_W * step;
  rotation_ += after_w_B * step;
  interval_ += step;
}

ImuSample Imu::Read(double t) {
  ImuSample s;
  s.t = t;
  s.interval = interval_;
  if (interval_ > 0) {
    // white noise of density N averaged over the interval T: N / sqrt(T); the biases walk
    const double root = std::sqrt(interval_);
    s.gyro_B = rotation_ / interval_ + gyro_bias_ + Noise(params_.gyro_noise_density / root);
    s.accel_B = velocity_ / interval_ + accel_bias_ + Noise(params_.accel_noise_density / root);
    gyro_bias_ += Noise(params_.gyro_bias_walk * root);
    accel_bias_ += Noise(params_.accel_bias_walk * root);
  }
  rotation_.setZero();
  velocity_.setZero();
  interval_ = 0.0;
  return s;
}

PositionSensorParams PositionSensorParams::Gps() {
  PositionSensorParams p;
  p.kind = PositionSensorKind::kGps;
  p.rate = 10.0;
  p.noise = Vec3(0.5, 0.5, 1.0);
  p.latency = 0.1;
  p.attitude_noise = 0.0;
  return p;
}

void PositionSensorParams::Describe(Archive& a) {
  a.Enum({"kind", "",
          "mocap (motion capture: 100 Hz, 1 mm, attitude too) or gps (10 Hz, 0.5 m / 1 m, no "
          "attitude): the defaults of the other keys, read first"},
         &kind, {{PositionSensorKind::kMocap, "mocap"}, {PositionSensorKind::kGps, "gps"}});
  a.Number({"rate", "Hz", "measurements per second (divides the physics rate)"}, &rate, 0.1, 1000);
  a.Vector({"noise", "m", "1 sigma per world axis"}, &noise, 1e-6, 100);
  a.Number({"latency", "s", "from the measurement to the estimator"}, &latency, 0, 0.5);
  a.Number({"attitude_noise", "rad", "1 sigma per body axis; 0: no attitude measured"},
           &attitude_noise, 0, 1);
}

void PositionSensorParams::Validate() const {
  ValidateFields(*this, "position");
  if (kind == PositionSensorKind::kGps && attitude_noise > 0) {
    throw std::invalid_argument("position.attitude_noise: a GPS measures no attitude");
  }
}

PositionSensor::PositionSensor(const PositionSensorParams& params, std::uint64_t seed)
    : params_(params), rng_(seed) {
  params_.Validate();
}

PoseMeasurement PositionSensor::Measure(double t, const State& truth) {
  PoseMeasurement m;
  m.t = t;
  const Vec3 n(normal_(rng_), normal_(rng_), normal_(rng_));
  m.p_W = truth.p_W + params_.noise.cwiseProduct(n);
  if (params_.attitude_noise > 0) {
    const Vec3 phi(normal_(rng_), normal_(rng_), normal_(rng_));
    m.q_WB = (truth.q_WB * RotationVectorToQuat(params_.attitude_noise * phi)).normalized();
  }
  return m;
}

}  // namespace aerobox
