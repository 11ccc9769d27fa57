// Each phase of a step is a loop over worlds written for the vectoriser (`omp simd`, selects in
// place of branches, no calls but sqrt); what cannot vectorise (the boxes' separating axes, the
// half angle's sine and cosine, the rare warning) has loops of its own.
#include "sim/rigid_batch.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "vehicle/model_names.h"

namespace aerobox {
namespace {

constexpr double kMinVal = 1e-15;  // MuJoCo's mjMINVAL
constexpr double kMaxVal = 1e10;   // MuJoCo's mjMAXVAL: beyond it a value is "bad"
constexpr size_t kLine = 8;        // doubles in a cache line
constexpr int kTile = 32;          // worlds stepped through every phase at once: in L1 together

// Doubles between columns: `worlds` rounded up to an odd number of cache lines, so that one
// world's columns spread over the cache's sets (a power of two would put them all in one).
size_t Stride(int worlds) {
  const size_t lines = (static_cast<size_t>(std::max(worlds, 0)) + kLine - 1) / kLine;
  return (lines | 1) * kLine;
}

// NaN or beyond mjMAXVAL.
inline bool Bad(double x) { return !(std::abs(x) <= kMaxVal); }

// `weight` when any of `n` columns from `first` (stride s) is Bad at world i, else 0: a double,
// for the vectoriser.
inline double AnyBad(const double* first, size_t s, int n, int i, double weight) {
  double bad = 0.0;
#pragma GCC unroll 8
  for (int c = 0; c < n; ++c) bad = Bad(first[c * s + i]) ? weight : bad;
  return bad;
}

// MuJoCo's mju_quat2Mat of (w, x, y, z).
Mat3 MatrixOf(double w, double x, double y, double z) {
  const double q00 = w * w, q01 = w * x, q02 = w * y, q03 = w * z;
  const double q11 = x * x, q12 = x * y, q13 = x * z;
  const double q22 = y * y, q23 = y * z, q33 = z * z;
  Mat3 R;
  R << q00 + q11 - q22 - q33, 2 * (q12 - q03), 2 * (q13 + q02),  //
      2 * (q12 + q03), q00 - q11 + q22 - q33, 2 * (q23 - q01),   //
      2 * (q13 - q02), 2 * (q23 + q01), q00 - q11 - q22 + q33;
  return R;
}

// MuJoCo's mju_normalize4 on (w, x, y, z): to unit length when off by more than mjMINVAL; the
// identity when too small to say. Branch-free, for the vectoriser.
inline void Normalize4(double* w, double* x, double* y, double* z) {
  const double norm = std::sqrt(*w * *w + *x * *x + *y * *y + *z * *z);
  const bool tiny = norm < kMinVal;
  const bool off = std::abs(norm - 1.0) > kMinVal;
  const double scale = 1.0 / (off & !tiny ? norm : 1.0);
  *w = tiny ? 1.0 : *w * scale;
  *x = tiny ? 0.0 : *x * scale;
  *y = tiny ? 0.0 : *y * scale;
  *z = tiny ? 0.0 : *z * scale;
}

// [m] from the hull's lowest corner (half sizes h, at p with attitude R) down to the floor.
double FloorDistance(const RigidModel& m, const Vec3& p, const Mat3& R) {
  return p.z() - R.row(2).cwiseAbs().dot(m.hull_half) - m.floor_z;
}

// [m] how deep the hull (half sizes h, at p with attitude R) and `box` overlap along the axis
// they overlap least (a separating-axis test): >= 0 when they touch; negative when apart (then
// only some separation, not the distance). The 3 + 3 face normals and their 9 cross products;
// along each unit axis the boxes overlap by their radii less the centres' distance. The first
// negative one, a separation, ends the test.
double Overlap(const Aabb& box, const Vec3& h, const Vec3& p, const Mat3& R) {
  const Vec3 d = box.Center() - p;
  const Vec3 e = box.HalfSize();
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

// The sine and cosine of x, |x| <= kSeriesReach, by their Taylor series to x^15 and x^16 (the
// next terms are below 1e-16 there): within an ulp of glibc's, the same bits for 95 % of 10 M
// random angles. For the vectoriser.
constexpr double kSeriesReach = 0.7853981633974483;  // [rad] pi / 4
inline void SinCosSeries(double x, double* sine, double* cosine) {
  const double x2 = x * x;
  constexpr double s3 = -1.0 / 6, s5 = 1.0 / 120, s7 = -1.0 / 5040, s9 = 1.0 / 362880,
                   s11 = -1.0 / 39916800, s13 = 1.0 / 6227020800, s15 = -1.0 / 1307674368000;
  constexpr double c2 = -0.5, c4 = 1.0 / 24, c6 = -1.0 / 720, c8 = 1.0 / 40320,
                   c10 = -1.0 / 3628800, c12 = 1.0 / 479001600, c14 = -1.0 / 87178291200,
                   c16 = 1.0 / 20922789888000;
  *sine =
      x + x * x2 * (s3 + x2 * (s5 + x2 * (s7 + x2 * (s9 + x2 * (s11 + x2 * (s13 + x2 * s15))))));
  *cosine =
      1.0 +
      x2 * (c2 +
            x2 * (c4 + x2 * (c6 + x2 * (c8 + x2 * (c10 + x2 * (c12 + x2 * (c14 + x2 * c16)))))));
}

// MuJoCo's mju_quatIntegrate of q (w, x, y, z) by the body rate (wx, wy, wz) [rad/s] over dt [s],
// given the sine and cosine of the half angle: q = normalised q (x) (cos, sin axis), the axis
// w / |w| (x when |w| is too small to say; mju_normalize3); no rotation at all for a zero angle
// (mju_axisAngle2Quat). Branch-free and of scalars only, for the vectoriser.
inline void Turn(double wx, double wy, double wz, double dt, double sine, double cosine, double* w,
                 double* x, double* y, double* z) {
  const double speed = std::sqrt(wx * wx + wy * wy + wz * wz);
  const bool still = speed < kMinVal;
  const double inverse = 1.0 / (still ? 1.0 : speed);
  const double ax = still ? 1.0 : wx * inverse, ay = still ? 0.0 : wy * inverse,
               az = still ? 0.0 : wz * inverse;
  const bool turns = dt * speed != 0.0;
  const double r0 = turns ? cosine : 1.0, r1 = turns ? sine * ax : 0.0,
               r2 = turns ? sine * ay : 0.0, r3 = turns ? sine * az : 0.0;
  double a0 = *w, a1 = *x, a2 = *y, a3 = *z;
  Normalize4(&a0, &a1, &a2, &a3);
  *w = a0 * r0 - a1 * r1 - a2 * r2 - a3 * r3;
  *x = a0 * r1 + a1 * r0 + a2 * r3 - a3 * r2;
  *y = a0 * r2 - a1 * r3 + a2 * r0 + a3 * r1;
  *z = a0 * r3 + a1 * r2 - a2 * r1 + a3 * r0;
}

}  // namespace

// The loops over worlds, each built for the widest vectors the processor has and chosen when the
// program starts (AVX-512, AVX2, else SSE2's two doubles); without FMA, so every width gives the
// same bits.
#define AEROBOX_WIDE __attribute__((target_clones("avx2", "default")))

RigidBatch::RigidBatch(RigidModel model, int worlds)
    : model_(std::move(model)), size_(worlds), stride_(Stride(worlds)) {
  if (worlds < 1) {
    throw std::invalid_argument("RigidBatch: at least one world, got " + std::to_string(worlds));
  }
  data_.assign(kColumns * stride_, 0.0);
  warnings_.resize(static_cast<size_t>(worlds));
  for (int i = 0; i < worlds; ++i) ScaleVehicle(i, VehicleScaling());
}

Vec3 RigidBatch::Get3(int c, int i) const { return Vec3(At(c, i), At(c + 1, i), At(c + 2, i)); }

Vec4 RigidBatch::Get4(int c, int i) const {
  return Vec4(At(c, i), At(c + 1, i), At(c + 2, i), At(c + 3, i));
}

void RigidBatch::Set3(int c, int i, const Vec3& v) {
  for (int k = 0; k < 3; ++k) At(c + k, i) = v[k];
}

void RigidBatch::Set4(int c, int i, const Vec4& v) {
  for (int k = 0; k < 4; ++k) At(c + k, i) = v[k];
}

void RigidBatch::SetExternalWrench(int i, const Vec3& force_W, const Vec3& torque_W) {
  Set3(kForce, i, force_W);
  Set3(kTorque, i, torque_W);
}

void RigidBatch::SetRotorThrusts(int i, const Vec4& thrusts) {
  Set4(kAct, i, thrusts);
  Set4(kCtrl, i, thrusts);
  Forward(i, i + 1);
}

void RigidBatch::ResetData(int i) {
  const Quat& q = model_.initial_q_WB;
  At(kTime, i) = 0.0;
  Set3(kP, i, model_.initial_p_W);
  Set4(kQ, i, Vec4(q.w(), q.x(), q.y(), q.z()));
  for (const int c : {kV, kW, kForce, kTorque}) Set3(c, i, Vec3::Zero());
  for (const int c : {kAct, kCtrl}) Set4(c, i, Vec4::Zero());
  warnings_[static_cast<size_t>(i)].clear();
  Forward(i, i + 1);
}

void RigidBatch::ScaleVehicle(int i, const VehicleScaling& s) {
  At(kMass, i) = model_.mass * s.mass;
  Set3(kInertia, i, model_.inertia.cwiseProduct(s.inertia));
  Set4(kGain, i, model_.gain.cwiseProduct(s.thrust));
  Set4(kYawMoment, i, model_.yaw_moment.cwiseProduct(s.yaw_moment));
  Set4(kLag, i, model_.lag.cwiseProduct(s.motor_lag));
  Set4(kCommandMax, i, model_.command_max.cwiseProduct(s.rotor_limit));
  ResetData(i);
}

State RigidBatch::VehicleState(int i) const {
  State s;
  s.p_W = Get3(kP, i);
  s.q_WB = Quat(At(kQ, i), At(kQ + 1, i), At(kQ + 2, i), At(kQ + 3, i));  // w, x, y, z
  s.v_W = Get3(kV, i);
  s.w_B = Get3(kW, i);
  return s;
}

void RigidBatch::SetVehicleState(int i, const State& state) {
  const Quat q = state.q_WB.normalized();
  Set3(kP, i, state.p_W);
  Set4(kQ, i, Vec4(q.w(), q.x(), q.y(), q.z()));
  Set3(kV, i, state.v_W);
  Set3(kW, i, state.w_B);
  Forward(i, i + 1);
}

std::string RigidBatch::TakeNewWarnings(int i) {
  std::string text;
  text.swap(warnings_[static_cast<size_t>(i)]);
  return text;
}

void RigidBatch::AddWarning(int i, const std::string& what) {
  std::string& w = warnings_[static_cast<size_t>(i)];
  if (!w.empty()) w += "; ";
  w += what;
}

void RigidBatch::Warn(int i, const std::string& what) {
  AddWarning(i, what + " (the rigid backend resets the world, as MuJoCo does)");
  std::string kept;
  kept.swap(warnings_[static_cast<size_t>(i)]);
  ResetData(i);
  warnings_[static_cast<size_t>(i)] = kept;
}

void RigidBatch::Step(int begin, int end) {
  for (int from = begin; from < end; from += kTile) {
    const int to = std::min(end, from + kTile);
    CheckBefore(from, to);
    Forward(from, to);
    CheckAfter(from, to);
    Integrate(from, to);
  }
}

AEROBOX_WIDE void RigidBatch::CheckBefore(int begin, int end) {
  double* const d = data_.data();
  const size_t s = stride_;
  double* const flags = d + kFlags * s;
#pragma omp simd
  for (int i = begin; i < end; ++i) {
    // the position and attitude (1), the velocities (2), the commands (4)
    flags[i] = AnyBad(d + kP * s, s, 7, i, 1.0) + AnyBad(d + kV * s, s, 6, i, 2.0) +
               AnyBad(d + kCtrl * s, s, 4, i, 4.0);
  }
  for (int i = begin; i < end; ++i) {
    const int found = static_cast<int>(flags[i]);
    if (found == 0) continue;
    if (found & 1) {
      Warn(i, "NaN, Inf or huge value in the position");
    } else if (found & 2) {
      Warn(i, "NaN, Inf or huge value in the velocity");
    }
    if (Bad(At(kCtrl, i)) || Bad(At(kCtrl + 1, i)) || Bad(At(kCtrl + 2, i)) ||
        Bad(At(kCtrl + 3, i))) {
      AddWarning(i, "NaN, Inf or huge value in the rotor commands (all set to 0)");
      Set4(kCtrl, i, Vec4::Zero());
    }
  }
}

AEROBOX_WIDE void RigidBatch::CheckAfter(int begin, int end) {
  double* const d = data_.data();
  const size_t s = stride_;
  double* const flags = d + kFlags * s;
#pragma omp simd
  for (int i = begin; i < end; ++i) flags[i] = AnyBad(d + kAcc * s, s, 6, i, 1.0);
  for (int i = begin; i < end; ++i) {
    if (flags[i] == 0) continue;
    Warn(i, "NaN, Inf or huge value in the acceleration");
    Forward(i, i + 1);
  }
}

AEROBOX_WIDE void RigidBatch::Forward(int begin, int end) {
  double* const d = data_.data();
  const size_t s = stride_;
  const auto col = [d, s](int c) { return d + c * s; };
  const RigidModel& m = model_;
  const double floor = model_.has_floor ? 1.0 : 0.0;  // no floor: nothing to touch
#pragma omp simd
  for (int i = begin; i < end; ++i) {
    double w = col(kQ)[i], x = col(kQ + 1)[i], y = col(kQ + 2)[i], z = col(kQ + 3)[i];
    Normalize4(&w, &x, &y, &z);
    col(kQ)[i] = col(kContactQ)[i] = w;
    col(kQ + 1)[i] = col(kContactQ + 1)[i] = x;
    col(kQ + 2)[i] = col(kContactQ + 2)[i] = y;
    col(kQ + 3)[i] = col(kContactQ + 3)[i] = z;
#pragma GCC unroll 3
    for (int k = 0; k < 3; ++k) col(kContactP + k)[i] = col(kP + k)[i];
    // mju_quat2Mat
    const double q00 = w * w, q01 = w * x, q02 = w * y, q03 = w * z;
    const double q11 = x * x, q12 = x * y, q13 = x * z;
    const double q22 = y * y, q23 = y * z, q33 = z * z;
    const double R[3][3] = {{q00 + q11 - q22 - q33, 2 * (q12 - q03), 2 * (q13 + q02)},
                            {2 * (q12 + q03), q00 - q11 + q22 - q33, 2 * (q23 - q01)},
                            {2 * (q13 - q02), 2 * (q23 + q01), q00 - q11 - q22 + q33}};
    // the floor: the hull's lowest corner
    const double lowest = col(kP + 2)[i] - (std::abs(R[2][0]) * m.hull_half.x() +
                                            std::abs(R[2][1]) * m.hull_half.y() +
                                            std::abs(R[2][2]) * m.hull_half.z());
    col(kTouches)[i] = lowest - m.floor_z <= 0.0 ? floor : 0.0;
    // actuation: the clamped commands, the thrusts of the motor lag's state
    double f[4], total = 0.0;
#pragma GCC unroll 4
    for (int k = 0; k < 4; ++k) {
      col(kClamped + k)[i] =
          std::min(std::max(col(kCtrl + k)[i], m.command_min[k]), col(kCommandMax + k)[i]);
      f[k] = col(kGain + k)[i] * col(kAct + k)[i];
      total += f[k];
    }
    // torques in the body's axes: the external one, the rotors' arms and reaction moments
    double torque[3];
#pragma GCC unroll 3
    for (int j = 0; j < 3; ++j) {
      torque[j] =
          R[0][j] * col(kTorque)[i] + R[1][j] * col(kTorque + 1)[i] + R[2][j] * col(kTorque + 2)[i];
    }
#pragma GCC unroll 4
    for (int k = 0; k < 4; ++k) {
      const Vec3& r = m.rotor_B[static_cast<size_t>(k)];
      torque[0] += f[k] * r.y();
      torque[1] += f[k] * -r.x();
      torque[2] += f[k] * col(kYawMoment + k)[i];
    }
    const double mass = col(kMass)[i];
#pragma GCC unroll 3
    for (int j = 0; j < 3; ++j) {
      col(kAcc + j)[i] = (R[j][2] * total + col(kForce + j)[i]) / mass + m.gravity[j];
    }
    // Euler's equations: I alpha = torque - w x I w
    const double wx = col(kW)[i], wy = col(kW + 1)[i], wz = col(kW + 2)[i];
    const double ix = col(kInertia)[i], iy = col(kInertia + 1)[i], iz = col(kInertia + 2)[i];
    const double lx = ix * wx, ly = iy * wy, lz = iz * wz;  // I w
    col(kAlpha)[i] = (torque[0] - (wy * lz - wz * ly)) / ix;
    col(kAlpha + 1)[i] = (torque[1] - (wz * lx - wx * lz)) / iy;
    col(kAlpha + 2)[i] = (torque[2] - (wx * ly - wy * lx)) / iz;
  }
  if (!model_.boxes.empty()) TouchBoxes(begin, end);
}

void RigidBatch::TouchBoxes(int begin, int end) {
  for (int i = begin; i < end; ++i) {
    if (At(kTouches, i) != 0.0) continue;
    const Vec3 p = Get3(kContactP, i);
    const Mat3 R = MatrixOf(At(kContactQ, i), At(kContactQ + 1, i), At(kContactQ + 2, i),
                            At(kContactQ + 3, i));
    for (const Aabb& box : model_.boxes) {
      if (Overlap(box, model_.hull_half, p, R) >= 0.0) {
        At(kTouches, i) = 1.0;
        break;
      }
    }
  }
}

AEROBOX_WIDE void RigidBatch::Integrate(int begin, int end) {
  double* const d = data_.data();
  const size_t s = stride_;
  const auto col = [d, s](int c) { return d + c * s; };
  const double dt = model_.timestep;
#pragma omp simd
  for (int i = begin; i < end; ++i) {
    // each rotor's lag, each axis's velocities and position (called, not looped: the vectoriser
    // takes a loop inside as the one to vectorise)
    const auto lag = [=](int k) {
      double& act = col(kAct + k)[i];
      const double tau = col(kLag + k)[i];
      act += dt * (col(kClamped + k)[i] - act) / (kMinVal < tau ? tau : kMinVal);
    };
    const auto axis = [=](int k) {
      col(kV + k)[i] += dt * col(kAcc + k)[i];
      col(kW + k)[i] += dt * col(kAlpha + k)[i];
      col(kP + k)[i] += dt * col(kV + k)[i];
    };
    lag(0), lag(1), lag(2), lag(3);
    axis(0), axis(1), axis(2);
    col(kTime)[i] += dt;
    // the attitude, where the half angle is within the series' reach; elsewhere no turn (q is
    // already normalised: Forward), then the library's sine and cosine below
    const double wx = col(kW)[i], wy = col(kW + 1)[i], wz = col(kW + 2)[i];
    const double half = 0.5 * (dt * std::sqrt(wx * wx + wy * wy + wz * wz));
    const bool near = std::abs(half) <= kSeriesReach;
    double sine, cosine;
    SinCosSeries(near ? half : 0.0, &sine, &cosine);
    Turn(wx, wy, wz, dt, sine, cosine, col(kQ) + i, col(kQ + 1) + i, col(kQ + 2) + i,
         col(kQ + 3) + i);
    col(kFlags)[i] = near ? 0.0 : 1.0;
  }
  for (int i = begin; i < end; ++i) {  // a turn beyond the series' reach: the library's
    if (col(kFlags)[i] == 0.0) continue;
    const double wx = col(kW)[i], wy = col(kW + 1)[i], wz = col(kW + 2)[i];
    const double half = 0.5 * (dt * std::sqrt(wx * wx + wy * wy + wz * wz));
    Turn(wx, wy, wz, dt, std::sin(half), std::cos(half), col(kQ) + i, col(kQ + 1) + i,
         col(kQ + 2) + i, col(kQ + 3) + i);
  }
}

std::vector<VehicleContact> RigidBatch::VehicleContacts(int i) const {
  std::vector<VehicleContact> contacts;
  const Vec3 p = Get3(kContactP, i);
  const Mat3 R =
      MatrixOf(At(kContactQ, i), At(kContactQ + 1, i), At(kContactQ + 2, i), At(kContactQ + 3, i));
  const double floor = model_.has_floor ? FloorDistance(model_, p, R) : 1.0;
  if (floor <= 0.0) {
    contacts.push_back({model_names::kFloorGeom, Vec3(p.x(), p.y(), model_.floor_z), floor});
  }
  for (size_t b = 0; b < model_.boxes.size(); ++b) {
    const double depth = Overlap(model_.boxes[b], model_.hull_half, p, R);
    if (depth < 0.0) continue;
    const Aabb& box = model_.boxes[b];
    contacts.push_back({model_.box_names[b], p.cwiseMax(box.min).cwiseMin(box.max), -depth});
  }
  return contacts;
}

}  // namespace aerobox
