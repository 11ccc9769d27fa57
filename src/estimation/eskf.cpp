#include "estimation/eskf.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>

namespace aerobox {
namespace {

constexpr int kP = 0, kV = 3, kTheta = 6, kBa = 9, kBg = 12;

Mat3 Skew(const Vec3& v) {
  Mat3 s;
  s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return s;
}

}  // namespace

Vec15 ErrorBetween(const NavState& truth, const NavState& estimate) {
  Vec15 e;
  e.segment<3>(kP) = truth.p_W - estimate.p_W;
  e.segment<3>(kV) = truth.v_W - estimate.v_W;
  e.segment<3>(kTheta) = QuatToRotationVector(estimate.q_WB.conjugate() * truth.q_WB);
  e.segment<3>(kBa) = truth.accel_bias - estimate.accel_bias;
  e.segment<3>(kBg) = truth.gyro_bias - estimate.gyro_bias;
  return e;
}

ErrorStateKalmanFilter::ErrorStateKalmanFilter(const ImuParams& imu,
                                               const PositionSensorParams& position,
                                               const NavState& initial, const Mat15& covariance,
                                               double t, double history, double world_step)
    : imu_(imu),
      position_(position),
      history_(history),
      world_step_(world_step),
      nominal_(initial),
      covariance_(covariance),
      time_(t) {}

void ErrorStateKalmanFilter::Advance(const ImuSample& s) {
  const double dt = s.interval;
  if (dt <= 0) return;
  const Mat3 R = nominal_.q_WB.toRotationMatrix();
  const Vec3 w = s.gyro_B - nominal_.gyro_bias;
  const Vec3 a = s.accel_B - nominal_.accel_bias;
  const Vec3 acc_W = R * a - Vec3(0, 0, kGravity);
  // the nominal state (see the constructor for the world's integration)
  const double lead = 0.5 * (1.0 + std::min(1.0, world_step_ / dt));
  nominal_.p_W += nominal_.v_W * dt + lead * acc_W * dt * dt;
  nominal_.v_W += acc_W * dt;
  const Quat turn = RotationVectorToQuat(w * dt);
  nominal_.q_WB = (nominal_.q_WB * turn).normalized();

  // the error state's transition and the noise the step adds (continuous densities times dt)
  Mat15 F = Mat15::Identity();
  F.block<3, 3>(kP, kV) = Mat3::Identity() * dt;
  F.block<3, 3>(kV, kTheta) = -R * Skew(a) * dt;
  F.block<3, 3>(kV, kBa) = -R * dt;
  F.block<3, 3>(kTheta, kTheta) = turn.toRotationMatrix().transpose();
  F.block<3, 3>(kTheta, kBg) = -Mat3::Identity() * dt;
  Mat15 Q = Mat15::Zero();
  const auto square = [](double x) { return x * x; };
  Q.block<3, 3>(kV, kV).diagonal().setConstant(square(imu_.accel_noise_density) * dt);
  Q.block<3, 3>(kTheta, kTheta).diagonal().setConstant(square(imu_.gyro_noise_density) * dt);
  Q.block<3, 3>(kBa, kBa).diagonal().setConstant(square(imu_.accel_bias_walk) * dt);
  Q.block<3, 3>(kBg, kBg).diagonal().setConstant(square(imu_.gyro_bias_walk) * dt);
  covariance_ = F * covariance_ * F.transpose() + Q;
  covariance_ = 0.5 * (covariance_ + covariance_.transpose());
  time_ = s.t;
}

void ErrorStateKalmanFilter::Propagate(const ImuSample& sample) {
  Advance(sample);
  entries_.push_back({time_, nominal_, covariance_, sample});
  while (!entries_.empty() && entries_.front().t < time_ - history_) entries_.pop_front();
}

void ErrorStateKalmanFilter::Correct(const PoseMeasurement& m) {
  const bool attitude = m.q_WB.has_value();
  const int rows = attitude ? 6 : 3;
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(rows, 15);
  Eigen::VectorXd r(rows);
  Eigen::MatrixXd noise = Eigen::MatrixXd::Zero(rows, rows);
  H.block<3, 3>(0, kP).setIdentity();
  r.head<3>() = m.p_W - nominal_.p_W;
  noise.block<3, 3>(0, 0).diagonal() = position_.noise.cwiseAbs2();
  if (attitude) {
    H.block<3, 3>(3, kTheta).setIdentity();
    r.tail<3>() = QuatToRotationVector(nominal_.q_WB.conjugate() * *m.q_WB);
    noise.block<3, 3>(3, 3).diagonal().setConstant(position_.attitude_noise *
                                                   position_.attitude_noise);
  }
  const Eigen::MatrixXd S = H * covariance_ * H.transpose() + noise;
  const Eigen::MatrixXd K =
      covariance_ * H.transpose() * S.llt().solve(Eigen::MatrixXd::Identity(rows, rows));
  const Vec15 dx = K * r;
  // Joseph form: stays symmetric and positive
  const Mat15 I_KH = Mat15::Identity() - K * H;
  covariance_ = I_KH * covariance_ * I_KH.transpose() + K * noise * K.transpose();
  nominal_.p_W += dx.segment<3>(kP);
  nominal_.v_W += dx.segment<3>(kV);
  nominal_.q_WB = (nominal_.q_WB * RotationVectorToQuat(dx.segment<3>(kTheta))).normalized();
  nominal_.accel_bias += dx.segment<3>(kBa);
  nominal_.gyro_bias += dx.segment<3>(kBg);
  // the reset: the covariance of the new error, whose attitude part is rotated by half the
  // correction
  Mat15 G = Mat15::Identity();
  G.block<3, 3>(kTheta, kTheta) -= 0.5 * Skew(dx.segment<3>(kTheta));
  covariance_ = G * covariance_ * G.transpose();
  covariance_ = 0.5 * (covariance_ + covariance_.transpose());
}

bool ErrorStateKalmanFilter::Update(const PoseMeasurement& m) {
  // the newest entry at or before the measurement's time
  auto at = std::find_if(entries_.rbegin(), entries_.rend(),
                         [&](const Entry& e) { return e.t <= m.t + 1e-9; });
  if (m.t >= time_ - 1e-9 || entries_.empty()) {
    Correct(m);
    if (!entries_.empty()) {
      entries_.back().nominal = nominal_;
      entries_.back().covariance = covariance_;
    }
    return true;
  }
  if (at == entries_.rend()) return false;  // older than the history
  auto it = at.base() - 1;                  // forward iterator to that entry
  nominal_ = it->nominal;
  covariance_ = it->covariance;
  time_ = it->t;
  Correct(m);
  it->nominal = nominal_;
  it->covariance = covariance_;
  for (++it; it != entries_.end(); ++it) {
    Advance(it->sample);
    it->nominal = nominal_;
    it->covariance = covariance_;
  }
  return true;
}

}  // namespace aerobox
