#include "vehicle/quad_params.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "common/number_format.h"

namespace aerobox {
namespace {

void RequirePositive(double value, const char* field) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw std::invalid_argument(std::string("QuadParams.") + field + " must be positive, got " +
                                FormatNumber(value));
  }
}

}  // namespace

void QuadParams::Validate() const {
  RequirePositive(mass, "mass");
  for (int i = 0; i < 3; ++i) RequirePositive(inertia[i], "inertia");
  for (int i = 0; i < 3; ++i) RequirePositive(collision_size[i], "collision_size");
  RequirePositive(arm_offset, "arm_offset");
  RequirePositive(max_rotor_thrust, "max_rotor_thrust");
  RequirePositive(yaw_moment_per_thrust, "yaw_moment_per_thrust");
  RequirePositive(motor_time_constant, "motor_time_constant");
  RequirePositive(propeller_radius, "propeller_radius");
  RequirePositive(guard_radius, "guard_radius");
  if (4.0 * max_rotor_thrust <= mass * kGravity) {
    throw std::invalid_argument("QuadParams.max_rotor_thrust " + FormatNumber(max_rotor_thrust) +
                                " N cannot lift the mass " + FormatNumber(mass) + " kg");
  }
  // the principal moments of a real body satisfy the triangle inequality
  if (inertia.x() + inertia.y() < inertia.z() || inertia.y() + inertia.z() < inertia.x() ||
      inertia.z() + inertia.x() < inertia.y()) {
    throw std::invalid_argument("QuadParams.inertia " + FormatVector(inertia) +
                                " violates the triangle inequality");
  }
}

Vec3 RotorPosition_B(const QuadParams& params, int rotor) {
  static constexpr double kSignX[kNumRotors] = {+1, -1, -1, +1};
  static constexpr double kSignY[kNumRotors] = {+1, +1, -1, -1};
  return params.arm_offset * Vec3(kSignX[rotor], kSignY[rotor], 0.0);
}

int RotorSpin(int rotor) { return rotor % 2 == 0 ? -1 : +1; }

double RotorYawMomentPerThrust(const QuadParams& params, int rotor) {
  return -RotorSpin(rotor) * params.yaw_moment_per_thrust;
}

Mat4 AllocationMatrix(const QuadParams& params) {
  Mat4 a;
  for (int i = 0; i < kNumRotors; ++i) {
    const Vec3 moment_arm = RotorPosition_B(params, i).cross(Vec3::UnitZ());
    a.col(i) << 1.0, moment_arm.x(), moment_arm.y(), RotorYawMomentPerThrust(params, i);
  }
  return a;
}

}  // namespace aerobox
