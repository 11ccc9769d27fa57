#include "sim/rigid_body.h"

#include <algorithm>
#include <cmath>

#include "vehicle/model_names.h"

namespace aerobox {
namespace {

constexpr double kMinVal = 1e-15;  // MuJoCo's mjMINVAL
constexpr double kMaxVal = 1e10;   // MuJoCo's mjMAXVAL: beyond it a value is "bad"

// Any component NaN or beyond mjMAXVAL.
template <typename V>
bool Bad(const V& v) {
  return !(v.array().abs() <= kMaxVal).all();
}

// q as (w, x, y, z), MuJoCo's order, and back.
Vec4 Wxyz(const Quat& q) { return Vec4(q.w(), q.x(), q.y(), q.z()); }

// MuJoCo's mju_normalize4: to unit length when off by more than mjMINVAL; the identity when
// too small to say.
void Normalize4(Vec4* q) {
  const double norm = q->norm();
  if (norm < kMinVal) {
    *q = Vec4(1, 0, 0, 0);
  } else if (std::abs(norm - 1.0) > kMinVal) {
    *q /= norm;
  }
}

// MuJoCo's mju_quat2Mat.
Mat3 MatrixOf(const Vec4& q) {
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
void Integrate(Vec4* q_wxyz, const Vec3& w, double dt) {
  const double speed = w.norm();
  const Vec3 axis = speed < kMinVal ? Vec3::UnitX() : Vec3(w / speed);
  const double angle = dt * speed;
  Vec4 r(1, 0, 0, 0);
  if (angle != 0.0) r << std::cos(0.5 * angle), std::sin(0.5 * angle) * axis;
  Normalize4(q_wxyz);
  const Vec4 a = *q_wxyz;
  Vec4& q = *q_wxyz;
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
  q_ = Wxyz(model_.initial_q_WB);
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

void RigidBody::AddWarning(const std::string& what) {
  if (!warnings_.empty()) warnings_ += "; ";
  warnings_ += what;
}

void RigidBody::Warn(const std::string& what) {
  AddWarning(what + " (the rigid backend resets the world, as MuJoCo does)");
  const std::string kept = warnings_;
  ResetData();
  warnings_ = kept;
}

double RigidBody::FloorDistance(const Vec3& p, const Mat3& R) const {
  // the hull's lowest corner: its centre less the half sizes along R's z row
  return p.z() - R.row(2).cwiseAbs().dot(model_.hull_half) - model_.floor_z;
}

void RigidBody::Forward() {
  Normalize4(&q_);
  const Mat3 R = MatrixOf(q_);
  // contacts: the hull's lowest corner against the floor, the hull against each box, in the
  // pose kept for VehicleContacts
  contact_p_W_ = p_W_;
  contact_R_ = R;
  touches_ = model_.has_floor && FloorDistance(p_W_, R) <= 0.0;
  for (size_t i = 0; i < model_.boxes.size() && !touches_; ++i) {
    touches_ = Overlap(model_.boxes[i], p_W_, R) >= 0.0;
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
  if (Bad(p_W_) || Bad(q_)) {
    Warn("NaN, Inf or huge value in the position");
  } else if (Bad(v_W_) || Bad(w_B_)) {
    Warn("NaN, Inf or huge value in the velocity");
  }
  if (Bad(ctrl_)) {
    AddWarning("NaN, Inf or huge value in the rotor commands (all set to 0)");
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
  Integrate(&q_, w_B_, dt);
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
  s.q_WB = Quat(q_[0], q_[1], q_[2], q_[3]);  // w, x, y, z
  s.v_W = v_W_;
  s.w_B = w_B_;
  return s;
}

void RigidBody::SetVehicleState(const State& state) {
  p_W_ = state.p_W;
  q_ = Wxyz(state.q_WB.normalized());
  v_W_ = state.v_W;
  w_B_ = state.w_B;
  Forward();
}

std::string RigidBody::TakeNewWarnings() {
  std::string text;
  text.swap(warnings_);
  return text;
}

double RigidBody::Overlap(const Aabb& box, const Vec3& p, const Mat3& R) const {
  // separating axes of an oriented box (centre p, axes R's columns, half sizes h) and an
  // axis-aligned one (centre c, half sizes e): the 3 + 3 face normals and their 9 cross
  // products; along each unit axis the boxes overlap by their radii less the centres' distance.
  // The least overlap is the depth (the boxes touch when it is >= 0, as MuJoCo's zero margin
  // counts touching); the first negative one, a separation, ends the test
  const Vec3 d = box.Center() - p;
  const Vec3 e = box.HalfSize();
  const Vec3& h = model_.hull_half;
  const Vec3 world = e + R.cwiseAbs() * h - d.cwiseAbs();  // along the world's axes, cheaply
  double least = world.minCoeff();
  const auto along = [&](const Vec3& axis) {
    const double radius = e.dot(axis.cwiseAbs()) + h.dot((R.transpose() * axis).cwiseAbs());
    least = std::min(least, radius - std::abs(d.dot(axis)));
    return least >= 0.0;
  };
  if (least < 0.0) return least;
  for (int j = 0; j < 3; ++j) {
    if (!along(R.col(j))) return least;
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Vec3 axis = Vec3::Unit(i).cross(R.col(j));
      const double norm = axis.norm();
      if (norm < 1e-10) continue;  // parallel: covered by the faces
      if (!along(axis / norm)) return least;
    }
  }
  return least;
}

std::vector<VehicleContact> RigidBody::VehicleContacts() const {
  std::vector<VehicleContact> contacts;
  const Vec3& p = contact_p_W_;
  const Mat3& R = contact_R_;
  const double floor = model_.has_floor ? FloorDistance(p, R) : 1.0;
  if (floor <= 0.0) {
    contacts.push_back({model_names::kFloorGeom, Vec3(p.x(), p.y(), model_.floor_z), floor});
  }
  for (size_t i = 0; i < model_.boxes.size(); ++i) {
    const double depth = Overlap(model_.boxes[i], p, R);
    if (depth < 0.0) continue;
    const Aabb& b = model_.boxes[i];
    contacts.push_back({model_.box_names[i], p.cwiseMax(b.min).cwiseMin(b.max), -depth});
  }
  return contacts;
}

}  // namespace aerobox
