#include "control/se3_control.h"

#include <cmath>
#include <stdexcept>

namespace aerobox {
namespace {

Mat3 Hat(const Vec3& w) {
  Mat3 m;
  m << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return m;
}

Vec3 Vee(const Mat3& m) { return Vec3(m(2, 1), m(0, 2), m(1, 0)); }

constexpr double kSteadySpeed = 0.2;  // [m/s] the integral's conditional integration

}  // namespace

void Se3Params::Validate() const {
  for (const auto& [gain, name] :
       {std::pair{&position_gain, "position_gain"}, std::pair{&velocity_gain, "velocity_gain"},
        std::pair{&attitude_gain, "attitude_gain"}, std::pair{&rate_gain, "rate_gain"}}) {
    if (!gain->allFinite() || (gain->array() <= 0).any()) {
      throw std::invalid_argument(std::string("Se3Params.") + name + " must be > 0");
    }
  }
  const Vec3 stable = position_gain.cwiseProduct(velocity_gain);  // Routh's bound
  if (!position_integral.allFinite() || (position_integral.array() < 0).any() ||
      (position_integral.array() >= stable.array()).any()) {
    throw std::invalid_argument(
        "Se3Params.position_integral must be >= 0 and below position_gain * velocity_gain");
  }
  if (!(integral_limit >= 0 && std::isfinite(integral_limit))) {
    throw std::invalid_argument("Se3Params.integral_limit must be >= 0");
  }
  if (!(max_tilt > 0 && max_tilt < M_PI / 2)) {
    throw std::invalid_argument("Se3Params.max_tilt must be in (0, pi/2)");
  }
}

Se3Controller::Se3Controller(const Se3Params& params, const QuadParams& vehicle)
    : params_(params), mass_(vehicle.mass), inertia_(vehicle.inertia) {
  params_.Validate();
}

Vec3 LimitTilt(Vec3 a, double max_tilt) {
  a.z() = std::max(a.z(), 0.1 * kGravity);
  const double max_horizontal = a.z() * std::tan(max_tilt);
  if (a.head<2>().norm() > max_horizontal) a.head<2>() *= max_horizontal / a.head<2>().norm();
  return a;
}

AttitudeTarget FlatAttitude(const Vec3& a, const FlatOutput& setpoint) {
  // desired attitude: body z along the force, body x towards the yaw heading
  const double c = a.norm();  // collective acceleration [m/s^2]
  const Vec3 b3 = a / c;
  const Vec3 heading(std::cos(setpoint.yaw), std::sin(setpoint.yaw), 0.0);
  Vec3 b2 = b3.cross(heading);
  if (b2.norm() < 1e-6) b2 = b3.cross(Vec3::UnitX());
  b2.normalize();
  const Vec3 b1 = b2.cross(b3);
  AttitudeTarget target;
  target.r_d << b1, b2, b3;

  // desired body rates and accelerations from jerk and snap: the force direction turns with
  // the jerk's part across it, d(c b3)/dt = j, d^2(c b3)/dt^2 = s
  const Vec3 h = (setpoint.j_W - b3.dot(setpoint.j_W) * b3) / c;  // = w x b3
  target.w_d = Vec3(-h.dot(b2), h.dot(b1), setpoint.yaw_rate * b3.z());
  const Vec3 w_W = target.r_d * target.w_d;
  const double c_dot = b3.dot(setpoint.j_W);
  const double c_ddot = b3.dot(setpoint.s_W) + c * w_W.cross(b3).squaredNorm();
  const Vec3 h2 =
      (setpoint.s_W - c_ddot * b3 - 2.0 * c_dot * w_W.cross(b3) - c * w_W.cross(w_W.cross(b3))) /
      c;  // = w_dot x b3
  target.w_dot_d = Vec3(-h2.dot(b2), h2.dot(b1), 0.0);
  return target;
}

Vec3 AttitudeAcceleration(const Se3Params& gains, const Mat3& r, const Vec3& w_B,
                          const AttitudeTarget& target, Vec3* e_R) {
  // errors on SO(3) and in the body rates (Lee et al., eqs. 10-11), and the angular
  // acceleration of the moment law (eq. 16)
  const Vec3 error = 0.5 * Vee(target.r_d.transpose() * r - r.transpose() * target.r_d);
  const Mat3 r_rel = r.transpose() * target.r_d;
  const Vec3 e_W = w_B - r_rel * target.w_d;
  if (e_R) *e_R = error;
  return -gains.attitude_gain.cwiseProduct(error) - gains.rate_gain.cwiseProduct(e_W) -
         Hat(w_B) * r_rel * target.w_d + r_rel * target.w_dot_d;
}

ControlStatus Se3Controller::Update(double t, const State& state, const FlatOutput& setpoint,
                                    ControlCommand* command) {
  if (!setpoint.AllFinite() || !state.AllFinite()) {
    return ControlStatus::NonFinite();
  }
  const Mat3 r = state.q_WB.normalized().toRotationMatrix();
  const Vec3 e_x = state.p_W - setpoint.p_W;
  const Vec3 e_v = state.v_W - setpoint.v_W;

  // the force (per unit mass): feedback, feed-forward, gravity; its tilt limited as the
  // cascade's, shrinking the horizontal part
  // the integral grows only near a steady state (the velocity error under 0.2 m/s), so that a
  // transient, a step or a take-off, does not wind it up
  const double dt = last_t_ && e_v.norm() < kSteadySpeed ? std::max(0.0, t - *last_t_) : 0.0;
  last_t_ = t;
  integral_ = (integral_ - dt * params_.position_integral.cwiseProduct(e_x))
                  .cwiseMax(-params_.integral_limit)
                  .cwiseMin(params_.integral_limit);
  const Vec3 a =
      LimitTilt(-params_.position_gain.cwiseProduct(e_x) - params_.velocity_gain.cwiseProduct(e_v) +
                    integral_ + setpoint.a_W + Vec3(0, 0, kGravity),
                params_.max_tilt);
  command->thrust = std::max(0.0, mass_ * a.dot(r.col(2)));
  const AttitudeTarget target = FlatAttitude(a, setpoint);
  const Vec3 alpha = AttitudeAcceleration(params_, r, state.w_B, target, &last_e_R_);
  const Vec3 jw = inertia_.cwiseProduct(state.w_B);
  command->level = CommandLevel::kThrustMoment;
  command->moment_B = inertia_.cwiseProduct(alpha) + state.w_B.cross(jw);
  last_w_d_ = target.w_d;
  return command->moment_B.allFinite() && std::isfinite(command->thrust)
             ? ControlStatus::Ok()
             : ControlStatus::NonFinite();
}

std::vector<std::string> Se3Controller::ReportColumns() const {
  return {"ex_R", "ey_R", "ez_R", "wx_d", "wy_d", "wz_d"};
}

void Se3Controller::Report(std::vector<double>* values) const {
  *values = {last_e_R_.x(), last_e_R_.y(), last_e_R_.z(),
             last_w_d_.x(), last_w_d_.y(), last_w_d_.z()};
}

}  // namespace aerobox
