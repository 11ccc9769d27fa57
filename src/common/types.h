// Eigen aliases and the small value types every module shares.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace aerobox {

using Vec3 = Eigen::Vector3d;
using Vec4 = Eigen::Vector4d;
using Mat3 = Eigen::Matrix3d;
using Mat4 = Eigen::Matrix4d;
using Quat = Eigen::Quaterniond;

// Standard gravity [m/s^2]; the world frame is ENU, so gravity points along -z.
inline constexpr double kGravity = 9.81;

// Axis-aligned box in the world frame [m]. Valid when min <= max on every axis.
struct Aabb {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();

  Vec3 Center() const { return 0.5 * (min + max); }
  Vec3 Size() const { return max - min; }
  Vec3 HalfSize() const { return 0.5 * (max - min); }
  // True when p lies inside or on the surface.
  bool Contains(const Vec3& p) const {
    return (p.array() >= min.array()).all() && (p.array() <= max.array()).all();
  }
  // True when this box lies inside or on the surface of `outer`.
  bool IsInside(const Aabb& outer) const {
    return (min.array() >= outer.min.array()).all() && (max.array() <= outer.max.array()).all();
  }
  // True when the interiors overlap (touching faces do not count).
  bool Overlaps(const Aabb& other) const {
    return (min.array() < other.max.array()).all() && (other.min.array() < max.array()).all();
  }
  // The box grown by `margin` [m] on every side.
  Aabb Inflated(double margin) const { return {min.array() - margin, max.array() + margin}; }
};

}  // namespace aerobox
