// The flat outputs a quadrotor follows (Mellinger and Kumar 2011): position and its derivatives
// up to snap, yaw and its rate, world frame (ENU). RotorPy's flat_output dict holds the same
// (x, x_dot, x_ddot, x_dddot, x_ddddot, yaw, yaw_dot).
#pragma once

#include <cmath>

#include "common/types.h"

namespace aerobox {

struct FlatOutput {
  Vec3 p_W = Vec3::Zero();  // position [m]
  Vec3 v_W = Vec3::Zero();  // velocity [m/s]
  Vec3 a_W = Vec3::Zero();  // acceleration [m/s^2]
  Vec3 j_W = Vec3::Zero();  // jerk [m/s^3]
  Vec3 s_W = Vec3::Zero();  // snap [m/s^4]
  double yaw = 0.0;         // [rad] about the world's z, 0 along +x
  double yaw_rate = 0.0;    // [rad/s]

  bool AllFinite() const {
    return p_W.allFinite() && v_W.allFinite() && a_W.allFinite() && j_W.allFinite() &&
           s_W.allFinite() && std::isfinite(yaw) && std::isfinite(yaw_rate);
  }
};

}  // namespace aerobox
