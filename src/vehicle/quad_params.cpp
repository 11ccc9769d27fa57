#include "vehicle/quad_params.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "common/number_format.h"

namespace aerobox {
namespace {

void RequirePositive(double value, const std::string& field) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw std::invalid_argument("QuadParams." + field + " must be positive, got " +
                                FormatNumber(value));
  }
}

// A Crazyflie 2.x, from RotorPy's crazyflie_params.py, which takes its rotor coefficients
// from Förster 2015 ("System identification of the Crazyflie 2.0 nano quadrocopter", ETH).
QuadParams Crazyflie() {
  QuadParams p;
  p.mass = 0.030;  // [kg] with battery (Bitcraze: 27 g bare)
  // [kg m^2] Förster 2015's identified moments. RotorPy's (1.43e-5, 1.43e-5, 2.89e-5) break the
  // triangle inequality Ixx + Iyy >= Izz that every rigid body meets (MuJoCo refuses them).
  p.inertia = Vec3(1.395e-5, 1.436e-5, 2.173e-5);
  // 43 mm arms at 45 degrees, RotorPy's order: front-left, front-right, back-right, back-left
  const double d = 0.043 * std::sqrt(0.5);
  p.rotor_positions_B = {Vec3(d, d, 0), Vec3(d, -d, 0), Vec3(-d, -d, 0), Vec3(-d, d, 0)};
  p.rotor_directions = {+1, -1, +1, -1};         // RotorPy's rotor_directions
  p.thrust_coefficient = 2.3e-8;                 // k_eta [N/(rad/s)^2]
  p.min_rotor_thrust = 0.0;                      // rotor_speed_min 0 rad/s
  p.max_rotor_thrust = p.ThrustAtSpeed(2500.0);  // rotor_speed_max 2500 rad/s: 0.144 N
  p.yaw_moment_per_thrust = 7.8e-10 / 2.3e-8;    // k_m / k_eta = 0.0339 m
  // RotorPy's crazyflie_params gives 0.005 s in its first releases and 0.072 s (on rotor
  // speed, which for small changes is the thrust's time constant too) in later ones; the
  // brushed motors are slow, so the later value is the one taken.
  p.motor_time_constant = 0.072;
  p.collision_size = Vec3(0.10, 0.10, 0.03);  // 92 x 92 x 29 mm over the propellers
  // 0.5 rho Cd A as for the Tello, with its 92 x 29 mm side faces and about half of its
  // 92 x 92 mm outline solid from above (an estimate); the rotor drag as the Tello's
  p.body_drag = Vec3(1.6e-3, 1.6e-3, 2.5e-3);
  // no published top speed; its thrust-to-weight of about 2 and flights in the Crazyswarm
  // papers put a safe cruise below 4 m/s (an estimate)
  p.max_speed = 4.0;
  p.propeller_radius = 0.0225;  // 45 mm propellers
  p.guard_radius = 0.024;       // (no guards: the propeller disc's outline)
  return p;
}

}  // namespace

void QuadParams::Describe(Archive& a) {
  a.Number({"mass", "kg", "with battery and guards"}, &mass, 1e-3, 100);
  a.Vector({"inertia", "kg m^2", "principal moments about the body axes (FLU)"}, &inertia, 1e-9,
           10);
  a.Number({"max_rotor_thrust", "N", "each rotor's most"}, &max_rotor_thrust, 0, 1000);
  a.Number({"min_rotor_thrust", "N", "each rotor's least"}, &min_rotor_thrust, 0, 1000);
  a.Number({"thrust_coefficient", "N/(rad/s)^2", "thrust per squared rotor speed (k_eta)"},
           &thrust_coefficient, 1e-15, 1);
  a.Number({"yaw_moment_per_thrust", "m", "reaction moment per newton of thrust (k_m / k_eta)"},
           &yaw_moment_per_thrust, 1e-6, 1);
  a.Number({"motor_time_constant", "s", "the thrust's first-order lag"}, &motor_time_constant, 1e-4,
           1);
  a.Number({"motor_noise", "rad/s", "rotor speed noise added once per control period"},
           &motor_noise, 0, 1e4);
  a.Vector({"collision_size", "m", "the collision box's full sides"}, &collision_size, 1e-3, 10);
  a.Vector({"body_drag", "N/(m/s)^2", "quadratic body drag per body axis (c_Dx, c_Dy, c_Dz)"},
           &body_drag, 0, 10);
  a.Vector({"rotor_drag", "s/m", "rotor drag per newton of thrust and m/s, per body axis"},
           &rotor_drag, 0, 10);
  a.Points({"rotor_positions", "m",
            "rotor centres, body frame: front-left, front-right, back-right, back-left"},
           rotor_positions_B.data(), kNumRotors, -10, 10);
  a.Signs({"rotor_directions", "", "the sign of the rotor's yaw moment on the body"},
          rotor_directions.data(), kNumRotors);
}

void QuadParams::Validate() const {
  RequirePositive(mass, "mass");
  for (int i = 0; i < 3; ++i) RequirePositive(inertia[i], "inertia");
  for (int i = 0; i < 3; ++i) RequirePositive(collision_size[i], "collision_size");
  for (int i = 0; i < 3; ++i) {
    if (!(body_drag[i] >= 0 && std::isfinite(body_drag[i])) ||
        !(rotor_drag[i] >= 0 && std::isfinite(rotor_drag[i]))) {
      throw std::invalid_argument("QuadParams.body_drag and rotor_drag must be >= 0, got " +
                                  FormatVector(body_drag) + " and " + FormatVector(rotor_drag));
    }
  }
  for (int i = 0; i < kNumRotors; ++i) {
    if (!rotor_positions_B[i].allFinite() || rotor_positions_B[i].head<2>().norm() < 1e-3) {
      throw std::invalid_argument("QuadParams.rotor_positions[" + std::to_string(i) +
                                  "] must be finite and off the body's z axis, got " +
                                  FormatVector(rotor_positions_B[i]));
    }
    if (rotor_directions[i] != 1 && rotor_directions[i] != -1) {
      throw std::invalid_argument("QuadParams.rotor_directions[" + std::to_string(i) +
                                  "] must be +1 or -1");
    }
  }
  if (!(std::isfinite(min_rotor_thrust) && min_rotor_thrust >= 0.0)) {
    throw std::invalid_argument("QuadParams.min_rotor_thrust must be >= 0, got " +
                                FormatNumber(min_rotor_thrust));
  }
  RequirePositive(max_rotor_thrust, "max_rotor_thrust");
  if (!(max_rotor_thrust > min_rotor_thrust)) {
    throw std::invalid_argument("QuadParams.max_rotor_thrust " + FormatNumber(max_rotor_thrust) +
                                " N must exceed min_rotor_thrust " +
                                FormatNumber(min_rotor_thrust) + " N");
  }
  RequirePositive(thrust_coefficient, "thrust_coefficient");
  RequirePositive(yaw_moment_per_thrust, "yaw_moment_per_thrust");
  RequirePositive(motor_time_constant, "motor_time_constant");
  if (!(std::isfinite(motor_noise) && motor_noise >= 0.0)) {
    throw std::invalid_argument("QuadParams.motor_noise must be >= 0 rad/s, got " +
                                FormatNumber(motor_noise));
  }
  RequirePositive(propeller_radius, "propeller_radius");
  RequirePositive(guard_radius, "guard_radius");
  if (kNumRotors * max_rotor_thrust <= mass * kGravity) {
    throw std::invalid_argument("QuadParams.max_rotor_thrust " + FormatNumber(max_rotor_thrust) +
                                " N cannot lift the mass " + FormatNumber(mass) + " kg");
  }
  // the principal moments of a real body satisfy the triangle inequality
  if (inertia.x() + inertia.y() < inertia.z() || inertia.y() + inertia.z() < inertia.x() ||
      inertia.z() + inertia.x() < inertia.y()) {
    throw std::invalid_argument("QuadParams.inertia " + FormatVector(inertia) +
                                " violates the triangle inequality");
  }
  // the four rotors must span thrust, roll, pitch and yaw, or no mixer exists
  if (std::abs(AllocationMatrix(*this).determinant()) < 1e-12 * max_rotor_thrust) {
    throw std::invalid_argument(
        "QuadParams.rotor_positions and rotor_directions cannot control roll, pitch and yaw "
        "independently (the allocation matrix is singular)");
  }
}

double QuadParams::RotorSpeedFor(double thrust) const {
  return std::sqrt(std::max(0.0, thrust) / thrust_coefficient);
}

double QuadParams::ArmLength() const {
  double arm = 0.0;
  for (const Vec3& r : rotor_positions_B) arm = std::max(arm, r.head<2>().norm());
  return arm;
}

std::optional<QuadParams> BuiltinVehicle(const std::string& kind) {
  if (kind == "tello") return QuadParams();
  if (kind == "crazyflie") return Crazyflie();
  return std::nullopt;
}

std::vector<std::string> BuiltinVehicleNames() { return {"crazyflie", "tello"}; }

DragModel LumpedDrag(const QuadParams& params) {
  return DragModel{params.rotor_drag * kGravity, params.body_drag / params.mass};
}

Vec3 RotorPosition_B(const QuadParams& params, int rotor) {
  return params.rotor_positions_B[rotor];
}

double RotorYawMomentPerThrust(const QuadParams& params, int rotor) {
  return params.rotor_directions[rotor] * params.yaw_moment_per_thrust;
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
