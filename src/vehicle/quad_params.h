// Physical parameters of a Tello-sized quadrotor (DJI Tello: 80 g, 98 x 92.5 x 41 mm).
// Every value carries its unit and where it comes from. The MuJoCo model in models/ and in every
// scene is generated from this struct, so these are the only copies of the numbers.
#pragma once

#include <array>

#include "common/types.h"

namespace aerobox {

struct QuadParams {
  // Mass with battery and guards [kg]. DJI's specification: 80 g.
  double mass = 0.080;

  // Principal moments of inertia about the body axes (FLU) [kg m^2]. A uniform 98 x 95 x 41 mm
  // box of 80 g gives Ixx = m (b^2 + c^2) / 12 = 7.1e-5, Iyy = 7.5e-5, Izz = 1.24e-4. The real
  // mass sits more at the centre (battery) and at the rotors (motors), which roughly cancel;
  // the RBE595 starter code's 0.0097 is about 100x too large for a vehicle this size.
  Vec3 inertia = Vec3(7.1e-5, 7.5e-5, 1.24e-4);

  // Rotor centres sit at (+-arm_offset, +-arm_offset, 0) in the body frame [m] (X layout). The
  // Tello's motors are about 7 cm apart front-to-back and side-to-side.
  double arm_offset = 0.035;

  // Largest thrust of one rotor [N]. Thrust-to-weight about 2: 4 x 0.4 N / (0.08 kg x 9.81).
  double max_rotor_thrust = 0.4;

  // Reaction (yaw) moment per newton of thrust [N m / N = m]. An estimate for 3-inch-class
  // propellers; it only sets the yaw authority, which the controller ranks last.
  double yaw_moment_per_thrust = 0.006;

  // First-order motor lag [s]. RotorS uses 1/80 s spinning up and 1/40 s down; MuJoCo 2.2's
  // filter actuator has one time constant, so 20 ms sits between the two.
  double motor_time_constant = 0.020;

  // Collision body: a box of these full sides [m], centred at the body origin. The Tello's
  // 98 x 92.5 x 41 mm rounded up to cover the guards.
  Vec3 collision_size = Vec3(0.10, 0.10, 0.05);

  // Visual only [m]: propeller radius and guard radius (the guards stay within the 0.10 m
  // collision box up to a few millimetres).
  double propeller_radius = 0.016;
  double guard_radius = 0.0175;

  // Throws std::invalid_argument naming the field and value when a value is not physical.
  void Validate() const;

  // Thrust of each rotor that holds a hover [N].
  double HoverThrustPerRotor() const { return mass * kGravity / 4.0; }
};

// Rotor numbering (looking down on the vehicle, x forward, y left):
//   rotor 0 front-left  (+x, +y), spins clockwise
//   rotor 1 back-left   (-x, +y), spins counter-clockwise
//   rotor 2 back-right  (-x, -y), spins clockwise
//   rotor 3 front-right (+x, -y), spins counter-clockwise
// Diagonal rotors spin the same way, so equal thrusts give no yaw moment.
inline constexpr int kNumRotors = 4;

// Rotor centre in the body frame [m].
Vec3 RotorPosition_B(const QuadParams& params, int rotor);

// +1 for a rotor that spins counter-clockwise seen from above (positive about body z), -1 for
// clockwise. The reaction moment on the body is opposite to the spin.
int RotorSpin(int rotor);

// Yaw moment on the body per newton of this rotor's thrust [m]: -spin * yaw_moment_per_thrust.
double RotorYawMomentPerThrust(const QuadParams& params, int rotor);

// Allocation matrix A: [total thrust N; roll, pitch, yaw moments N m (body frame)] = A * f,
// where f holds the four rotor thrusts [N]. Moments are r_i x (0, 0, f_i) plus the reaction.
Mat4 AllocationMatrix(const QuadParams& params);

}  // namespace aerobox
