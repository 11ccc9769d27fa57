#include "sim/rigid_body.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sim/simulation.h"
#include "vehicle/model_names.h"

namespace aerobox {
namespace {

constexpr double kMinVal = 1e-15;  // MuJoCo's mjMINVAL
constexpr double kMaxVal = 1e10;   // MuJoCo's mjMAXVAL: beyond it a value is "bad"

bool Bad(double x) { return !(x >= -kMaxVal && x <= kMaxVal); }
bool Bad(const Vec3& v) { return Bad(v.x()) || Bad(v.y()) || Bad(v.z()); }

// MuJoCo's mju_normalize4: to unit length when off by more than mjMINVAL; the identity when
// too small to say.
void Normalize4(double q[4]) {
  const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (norm < kMinVal) {
    q[0] = 1;
    q[1] = q[2] = q[3] = 0;
  } else if (std::abs(norm - 1.0) > kMinVal) {
    for (int i = 0; i < 4; ++i) q[i] /= norm;
  }
}

// MuJoCo's mju_quat2Mat.
Mat3 MatrixOf(const double q[4]) {
  const double q00 = q[0] * q[0], q01 = q[0] * q[1], q02 = q[0] * q[2], q03 = q[0] * q[3];
  const double q11 = q[1] * q[1], q12 = q[1] * q[2], q13 = q[1] * q[3];
  const double q22 = q[2] * q[2], q23 = q[2] * q[3], q33 = q[3] * q[3];
  Mat3 R;
  R << q00 + q11 - q22 - q33, 2 * (q12 - q03), 2 * (q13 + q02),  //
      2 * (q12 + q03), q00 - q11 + q22 - q33, 2 * (q23 - q01),   //
      2 * (q13 - q02), 2 * (q23 + q01), q00 - q11 - q22 + q33;
  return R;
}

// MuJoCo's mju_quatIntegrate: q = normalised q (x) the rotation of `w` [rad/s, body axes] over
// `dt` [s].
void Integrate(double q[4], const Vec3& w, double dt) {
  const double speed = w.norm();
  const Vec3 axis = speed < kMinVal ? Vec3::UnitX() : Vec3(w / speed);
  const double angle = dt * speed;
  double r[4] = {1, 0, 0, 0};
  if (angle != 0.0) {
    const double s = std::sin(0.5 * angle);
    r[0] = std::cos(0.5 * angle);
    r[1] = axis.x() * s;
    r[2] = axis.y() * s;
    r[3] = axis.z() * s;
  }
  Normalize4(q);
  const double a[4] = {q[0], q[1], q[2], q[3]};
  q[0] = a[0] * r[0] - a[1] * r[1] - a[2] * r[2] - a[3] * r[3];
  q[1] = a[0] * r[1] + a[1] * r[0] + a[2] * r[3] - a[3] * r[2];
  q[2] = a[0] * r[2] - a[1] * r[3] + a[2] * r[0] + a[3] * r[1];
  q[3] = a[0] * r[3] + a[1] * r[2] - a[2] * r[1] + a[3] * r[0];
}

}  // namespace

RigidBody::RigidBody(RigidModel model) : made_(model), model_(std::move(model)) { ResetData(); }

void RigidBody::ResetData() {
  time_ = 0.0;
  p_W_ = model_.initial_p_W;
  const Quat& q = model_.initial_q_WB;
  q_[0] = q.w();
  q_[1] = q.x();
  q_[2] = q.y();
  q_[3] = q.z();
  v_W_.setZero();
  w_B_.setZero();
  act_.setZero();
  ctrl_.setZero();
  force_W_.setZero();
  torque_W_.setZero();
  warnings_.clear();
  Forward();
}

void RigidBody::ScaleVehicle(const VehicleScaling& s) {
  model_ = made_;
  model_.mass *= s.mass;
  model_.inertia = made_.inertia.cwiseProduct(s.inertia);
  model_.gain = made_.gain.cwiseProduct(s.thrust);
  model_.yaw_moment = made_.yaw_moment.cwiseProduct(s.yaw_moment);
  model_.lag = made_.lag.cwiseProduct(s.motor_lag);
  model_.command_max = made_.command_max.cwiseProduct(s.rotor_limit);
  ResetData();
}

void RigidBody::Warn(const std::string& what) {
  if (!warnings_.empty()) warnings_ += "; ";
  warnings_ += what + " (the rigid backend resets the world, as MuJoCo does)";
  const std::string kept = warnings_;
  ResetData();
  warnings_ = kept;
}

void RigidBody::Forward() {
  Normalize4(q_);
  const Mat3 R = MatrixOf(q_);
  // contacts: the hull's lowest corner against the floor, the hull against each box
  touches_ = false;
  if (model_.has_floor) {
    const double reach = R.row(2).cwiseAbs().dot(model_.hull_half);  // the lowest corner's depth
    touches_ = p_W_.z() - reach - model_.floor_z <= 0.0;
  }
  for (size_t i = 0; i < model_.boxes.size() && !touches_; ++i) {
    touches_ = Touches(model_.boxes[i], R);
  }
  // actuation: the clamped commands, the thrusts of the motor lag's state
  clamped_ = ctrl_.cwiseMax(model_.command_min).cwiseMin(model_.command_max);
  const Vec4 f = model_.gain.cwiseProduct(act_);
  Vec3 torque_B = R.transpose() * torque_W_;
  for (int i = 0; i < 4; ++i) {
    const Vec3& r = model_.rotor_B[static_cast<size_t>(i)];
    torque_B += f[i] * Vec3(r.y(), -r.x(), model_.yaw_moment[i]);
  }
  const Vec3 force_W = R.col(2) * f.sum() + force_W_;
  acc_W_ = force_W / model_.mass + model_.gravity;
  const Vec3 Iw = model_.inertia.cwiseProduct(w_B_);
  alpha_B_ = (torque_B - w_B_.cross(Iw)).cwiseQuotient(model_.inertia);
}

void RigidBody::Step(const Vec4& thrust_commands) {
  ctrl_ = thrust_commands;
  // MuJoCo's checks before and after its forward pass, each a reset when it fails
  if (Bad(p_W_) || Bad(Vec3(q_[0], q_[1], q_[2])) || Bad(q_[3])) {
    Warn("NaN, Inf or huge value in the position");
  } else if (Bad(v_W_) || Bad(w_B_)) {
    Warn("NaN, Inf or huge value in the velocity");
  }
  if (Bad(ctrl_.head<3>()) || Bad(ctrl_[3])) {
    if (!warnings_.empty()) warnings_ += "; ";
    warnings_ += "NaN, Inf or huge value in the rotor commands (all set to 0)";
    ctrl_.setZero();
  }
  Forward();
  if (Bad(acc_W_) || Bad(alpha_B_)) {
    Warn("NaN, Inf or huge value in the acceleration");
    Forward();
  }
  // semi-implicit Euler, in mj_Euler's order: the motor lag, the velocities, the positions
  const double dt = model_.timestep;
  for (int i = 0; i < 4; ++i) {
    act_[i] += dt * (clamped_[i] - act_[i]) / std::max(kMinVal, model_.lag[i]);
  }
  v_W_ += dt * acc_W_;
  w_B_ += dt * alpha_B_;
  p_W_ += dt * v_W_;
  Integrate(q_, w_B_, dt);
  time_ += dt;
}

void RigidBody::SetExternalWrench(const Vec3& force_W, const Vec3& torque_W) {
  force_W_ = force_W;
  torque_W_ = torque_W;
}

Vec4 RigidBody::RotorThrusts() const { return act_; }

void RigidBody::SetRotorThrusts(const Vec4& thrusts) {
  act_ = thrusts;
  ctrl_ = thrusts;
  Forward();
}

State RigidBody::VehicleState() const {
  State s;
  s.p_W = p_W_;
  s.q_WB = Quat(q_[0], q_[1], q_[2], q_[3]);
  s.v_W = v_W_;
  s.w_B = w_B_;
  return s;
}

void RigidBody::SetVehicleState(const State& state) {
  p_W_ = state.p_W;
  const Quat q = state.q_WB.normalized();
  q_[0] = q.w();
  q_[1] = q.x();
  q_[2] = q.y();
  q_[3] = q.z();
  v_W_ = state.v_W;
  w_B_ = state.w_B;
  Forward();
}

std::string RigidBody::TakeNewWarnings() {
  std::string text;
  text.swap(warnings_);
  return text;
}

bool RigidBody::Touches(const Aabb& box, const Mat3& R) const {
  // separating axes of an oriented box (centre p, axes R's columns, half sizes h) and an
  // axis-aligned one (centre c, half sizes e): the 3 + 3 face normals and their 9 cross products;
  // touching (a separation of exactly 0) counts, as MuJoCo's zero margin does
  const Vec3 d = box.Center() - p_W_;
  const Vec3 e = box.HalfSize();
  const Vec3& h = model_.hull_half;
  const Mat3 A = R.cwiseAbs();
  const auto separated = [&](const Vec3& axis) {
    const double radius = e.dot(axis.cwiseAbs()) + h.dot((R.transpose() * axis).cwiseAbs());
    return std::abs(d.dot(axis)) > radius;
  };
  // the world's axes, cheaply first (the hull's extent along each is A h)
  if (((d.cwiseAbs() - e - A * h).array() > 0.0).any()) return false;
  for (int j = 0; j < 3; ++j) {
    if (separated(R.col(j))) return false;
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Vec3 axis = Vec3::Unit(i).cross(R.col(j));
      if (axis.squaredNorm() < 1e-20) continue;  // parallel: covered by the faces
      if (separated(axis)) return false;
    }
  }
  return true;
}

std::vector<VehicleContact> RigidBody::VehicleContacts() const {
  std::vector<VehicleContact> contacts;
  const Mat3 R = MatrixOf(q_);
  if (model_.has_floor) {
    const double reach = R.row(2).cwiseAbs().dot(model_.hull_half);
    const double distance = p_W_.z() - reach - model_.floor_z;
    if (distance <= 0.0) {
      contacts.push_back(
          {model_names::kFloorGeom, Vec3(p_W_.x(), p_W_.y(), model_.floor_z), distance});
    }
  }
  for (size_t i = 0; i < model_.boxes.size(); ++i) {
    if (!Touches(model_.boxes[i], R)) continue;
    const Aabb& b = model_.boxes[i];
    const Vec3 nearest = p_W_.cwiseMax(b.min).cwiseMin(b.max);
    contacts.push_back({model_.box_names[i], nearest, -0.0});
  }
  return contacts;
}

}  // namespace aerobox
