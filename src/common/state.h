// Rigid-body state of the vehicle in our conventions (ENU world, FLU body, SI units).
#pragma once

#include "common/types.h"

namespace aerobox {

struct State {
  Vec3 p_W = Vec3::Zero();       // position of the body origin in the world [m]
  Vec3 v_W = Vec3::Zero();       // velocity in the world frame [m/s]
  Quat q_WB = Quat::Identity();  // attitude: rotates body vectors into the world
  Vec3 w_B = Vec3::Zero();       // angular velocity in the body frame [rad/s]

  bool AllFinite() const {
    return p_W.allFinite() && v_W.allFinite() && q_WB.coeffs().allFinite() && w_B.allFinite();
  }
};

// MuJoCo stores quaternions as (w, x, y, z); Eigen's constructor takes the same order but its
// storage is (x, y, z, w). These two functions are the only place that order is handled.
inline Quat QuatFromWxyz(const double* wxyz) { return Quat(wxyz[0], wxyz[1], wxyz[2], wxyz[3]); }
inline void QuatToWxyz(const Quat& q, double* wxyz) {
  wxyz[0] = q.w();
  wxyz[1] = q.x();
  wxyz[2] = q.y();
  wxyz[3] = q.z();
}

}  // namespace aerobox
