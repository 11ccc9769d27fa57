// The sensors: the IMU's noise against its density (Allan deviation), its biases, the position
// sensor's noise, and seeded reproducibility.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "estimation/sensors.h"

namespace aerobox {
namespace {

// Allan deviation at cluster time tau = m samples of a series sampled every `dt` seconds
// (non-overlapping clusters).
double AllanDeviation(const std::vector<double>& x, size_t m) {
  std::vector<double> means;
  for (size_t i = 0; i + m <= x.size(); i += m) {
    double sum = 0.0;
    for (size_t k = 0; k < m; ++k) sum += x[i + k];
    means.push_back(sum / static_cast<double>(m));
  }
  double square = 0.0;
  for (size_t i = 1; i < means.size(); ++i) square += std::pow(means[i] - means[i - 1], 2);
  return std::sqrt(0.5 * square / static_cast<double>(means.size() - 1));
}

TEST_CASE("a still IMU's Allan deviation at 1 s is its noise density") {
  ImuParams p;
  p.enabled = true;
  Imu imu(p, 42);
  const double step = 1.0 / p.rate;
  const long n = 2000 * static_cast<long>(p.rate);  // 2000 s
  std::vector<double> gyro[3], accel[3];
  const State still;  // level, at rest on a table: the accelerometer reads +g up
  for (long i = 0; i < n; ++i) {
    imu.Accumulate(step, still, Vec3::Zero(), Vec3::Zero());
    const ImuSample s = imu.Read((i + 1) * step);
    for (int k = 0; k < 3; ++k) {
      gyro[k].push_back(s.gyro_B[k]);
      accel[k].push_back(s.accel_B[k]);
    }
  }
  const size_t second = static_cast<size_t>(p.rate);
  for (int k = 0; k < 3; ++k) {
    CAPTURE(k);
    // the white noise's part is N / sqrt(tau); the bias walk adds K sqrt(tau / 3), a few per
    // cent of it at 1 s with these parts
    CHECK(AllanDeviation(gyro[k], second) == doctest::Approx(p.gyro_noise_density).epsilon(0.10));
    CHECK(AllanDeviation(accel[k], second) == doctest::Approx(p.accel_noise_density).epsilon(0.10));
  }
  // the readings sit at the turn-on bias (+ g on the accelerometer's z)
  double mean_z = 0.0;
  for (const double a : accel[2]) mean_z += a;
  mean_z /= static_cast<double>(n);
  CHECK(std::abs(mean_z - kGravity) < 5 * p.accel_turn_on_bias);
}

TEST_CASE("an IMU averages over its interval and reads the specific force in its body frame") {
  ImuParams p;
  p.enabled = true;
  p.gyro_noise_density = p.accel_noise_density = 0.0;
  p.gyro_bias_walk = p.accel_bias_walk = 0.0;
  p.gyro_turn_on_bias = p.accel_turn_on_bias = 0.0;
  Imu imu(p, 1);
  State tilted;
  tilted.q_WB = Quat(Eigen::AngleAxisd(0.5 * M_PI, Vec3::UnitX()));  // body y points up
  imu.Accumulate(0.001, tilted, Vec3(0, 0, 1), Vec3(0, 0, 2));
  imu.Accumulate(0.001, tilted, Vec3(0, 0, 3), Vec3(0, 0, 2));
  const ImuSample s = imu.Read(0.002);
  CHECK(s.interval == doctest::Approx(0.002));
  CHECK(s.gyro_B.z() == doctest::Approx(2.0));
  CHECK(s.accel_B.y() == doctest::Approx(kGravity + 2.0));
  CHECK(std::abs(s.accel_B.z()) < 1e-9);
}

TEST_CASE("the position sensor's noise has its standard deviation, and its seed repeats") {
  PositionSensorParams p;
  p.enabled = true;
  p.noise = Vec3(0.01, 0.02, 0.03);
  PositionSensor a(p, 9), b(p, 9);
  State truth;
  truth.p_W = Vec3(1, 2, 3);
  Vec3 square = Vec3::Zero();
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const PoseMeasurement m = a.Measure(i * 0.01, truth);
    const PoseMeasurement same = b.Measure(i * 0.01, truth);
    REQUIRE(m.p_W == same.p_W);
    REQUIRE(m.q_WB.has_value());  // motion capture tracks attitude
    square += (m.p_W - truth.p_W).cwiseAbs2();
  }
  const Vec3 sigma = (square / n).cwiseSqrt();
  for (int k = 0; k < 3; ++k) CHECK(sigma[k] == doctest::Approx(p.noise[k]).epsilon(0.02));
  CHECK_FALSE(PositionSensor(PositionSensorParams::Gps(), 1).Measure(0, truth).q_WB);
}

TEST_CASE("rotation vectors and quaternions convert both ways") {
  for (const Vec3& phi : {Vec3(0.1, -0.2, 0.3), Vec3(1e-14, 0, 0), Vec3(0, 3.0, 0)}) {
    CHECK((QuatToRotationVector(RotationVectorToQuat(phi)) - phi).norm() < 1e-12);
  }
}

TEST_CASE("bad sensor parameters are refused, naming the field") {
  ImuParams imu;
  imu.gyro_noise_density = -1;
  CHECK_THROWS_WITH_AS(imu.Validate(), doctest::Contains("imu.gyro_noise_density"),
                       std::invalid_argument);
  PositionSensorParams gps = PositionSensorParams::Gps();
  gps.attitude_noise = 0.01;
  CHECK_THROWS_WITH_AS(gps.Validate(), doctest::Contains("GPS"), std::invalid_argument);
}

}  // namespace
}  // namespace aerobox
