#include "estimation/sensing.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "common/rates.h"
#include "common/seed.h"

namespace aerobox {
namespace {

Mat15 InitialCovariance(const SensorParams& p) {
  Vec15 sigma;
  sigma << Vec3::Constant(p.estimator.position_sigma), Vec3::Constant(p.estimator.velocity_sigma),
      Vec3::Constant(p.estimator.attitude_sigma), Vec3::Constant(p.imu.accel_turn_on_bias),
      Vec3::Constant(p.imu.gyro_turn_on_bias);
  // a bias the datasheet calls exact still gets a little room
  sigma = sigma.cwiseMax(1e-6);
  return sigma.cwiseAbs2().asDiagonal();
}

NavState InitialEstimate(const SensorParams& p, std::uint64_t seed, const State& truth) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  const auto draw = [&](double sigma) -> Vec3 { return Vec3(n(rng), n(rng), n(rng)) * sigma; };
  NavState s;
  s.p_W = truth.p_W + draw(p.estimator.position_sigma);
  s.v_W = truth.v_W + draw(p.estimator.velocity_sigma);
  // the truth is the estimate turned by the error: the estimate is the truth turned back
  s.q_WB = (truth.q_WB * RotationVectorToQuat(-draw(p.estimator.attitude_sigma))).normalized();
  return s;
}

}  // namespace

void EstimatorParams::Describe(Archive& a) {
  a.Number({"position_sigma", "m", "the filter's initial position uncertainty, 1 sigma"},
           &position_sigma, 1e-6, 100);
  a.Number({"velocity_sigma", "m/s", "the filter's initial velocity uncertainty"}, &velocity_sigma,
           1e-6, 100);
  a.Number({"attitude_sigma", "rad", "the filter's initial attitude uncertainty"}, &attitude_sigma,
           1e-6, 3);
  a.Number({"history", "s", "how late a measurement may arrive and still count"}, &history, 0.01,
           10);
}

void EstimatorParams::Validate() const {
  const auto positive = [](double v, const char* field) {
    if (!(v > 0 && std::isfinite(v)))
      throw std::invalid_argument(std::string("estimator.") + field + ": expected > 0");
  };
  positive(position_sigma, "position_sigma");
  positive(velocity_sigma, "velocity_sigma");
  positive(attitude_sigma, "attitude_sigma");
  positive(history, "history");
}

void SensorParams::Validate(double step) const {
  if (!Enabled()) return;
  if (!imu.enabled || !position.enabled) {
    throw std::invalid_argument(
        std::string("sensors.") + (imu.enabled ? "position" : "imu") +
        ": the estimator needs both the IMU and the position sensor (turn both on, or neither)");
  }
  imu.Validate();
  position.Validate();
  estimator.Validate();
  StepsPerPeriod(imu.rate, step, "sensors.imu.rate:");
  StepsPerPeriod(position.rate, step, "sensors.position.rate:");
  if (position.latency > estimator.history) {
    throw std::invalid_argument("sensors.position.latency: longer than the estimator's history");
  }
}

SensorSuite::SensorSuite(const SensorParams& params, std::uint64_t seed, double step, double t,
                         const State& truth)
    : params_(params),
      imu_(params.imu, StreamSeed(seed, SeedStream::kImu)),
      position_(params.position, StreamSeed(seed, SeedStream::kPositionSensor)),
      filter_(params.imu, params.position,
              InitialEstimate(params, StreamSeed(seed, SeedStream::kInitialEstimate), truth),
              InitialCovariance(params), t, params.estimator.history, step) {
  params_.Validate(step);
  imu_divider_ = StepsPerPeriod(params.imu.rate, step, "sensors.imu.rate:");
  position_divider_ = StepsPerPeriod(params.position.rate, step, "sensors.position.rate:");
  step_ = step;
  last_imu_.t = t;
  last_imu_.gyro_B = truth.w_B;
  // until the first reading: the specific force of a vehicle held still (what hover thrust or
  // the floor gives), so that Acceleration_W reads no acceleration rather than a free fall
  last_imu_.accel_B = truth.q_WB.normalized().inverse() * Vec3(0, 0, kGravity);
}

void SensorSuite::AfterStep(double t, const State& before, const State& now, const Vec3& a_W) {
  imu_.Accumulate(step_, before, now.w_B, a_W);
  ++steps_;
  if (steps_ % imu_divider_ == 0) {
    last_imu_ = imu_.Read(t);
    filter_.Propagate(last_imu_);
  }
  if (steps_ % position_divider_ == 0) in_flight_.push_back(position_.Measure(t, now));
  while (!in_flight_.empty() && in_flight_.front().t + params_.position.latency <= t + 1e-9) {
    filter_.Update(in_flight_.front());
    last_pose_ = in_flight_.front();
    in_flight_.pop_front();
  }
}

State SensorSuite::Estimate() const {
  const NavState& s = filter_.nominal();
  return State{s.p_W, s.v_W, s.q_WB, last_imu_.gyro_B - s.gyro_bias};
}

Vec3 SensorSuite::Acceleration_W() const {
  const NavState& s = filter_.nominal();
  return s.q_WB * (last_imu_.accel_B - s.accel_bias) - Vec3(0, 0, kGravity);
}

EstimateSample SensorSuite::Sample(const State& truth) const {
  EstimateSample s;
  s.estimate = Estimate();
  s.error = ErrorBetween(TruthOf(truth), filter_.nominal());
  const Mat15& P = filter_.covariance();
  s.sigma = P.diagonal().cwiseMax(0.0).cwiseSqrt();
  s.nees = s.error.dot(P.ldlt().solve(s.error));
  s.imu = last_imu_;
  s.pose = last_pose_;
  return s;
}

NavState SensorSuite::TruthOf(const State& truth) const {
  return NavState{truth.p_W, truth.v_W, truth.q_WB, imu_.accel_bias(), imu_.gyro_bias()};
}

}  // namespace aerobox
