// Physical parameters of a quadrotor. Every value carries its unit and where it comes from. The
// MuJoCo model in models/ and in every scene, the collision world and the controllers are all
// made from this struct, so these are the only copies of the numbers. Two built-in vehicles
// (BuiltinVehicle): "tello", the default, and "crazyflie".
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "common/drag.h"
#include "common/schema.h"
#include "common/types.h"

namespace aerobox {

inline constexpr int kNumRotors = 4;

struct QuadParams {
  // Defaults: a DJI Tello (80 g, 98 x 92.5 x 41 mm).

  // Mass with battery and guards [kg]. DJI's specification: 80 g.
  double mass = 0.080;

  // Principal moments of inertia about the body axes (FLU) [kg m^2]. A uniform 98 x 95 x 41 mm
  // box of 80 g gives Ixx = m (b^2 + c^2) / 12 = 7.1e-5, Iyy = 7.5e-5, Izz = 1.24e-4. The real
  // mass sits more at the centre (battery) and at the rotors (motors), which roughly cancel;
  // the RBE595 starter code's 0.0097 is about 100x too large for a vehicle this size.
  Vec3 inertia = Vec3(7.1e-5, 7.5e-5, 1.24e-4);

  // Rotor centres in the body frame [m]. The Tello's motors are about 7 cm apart front-to-back
  // and side-to-side (X layout). The index is the rotor's number everywhere (commands, motor
  // lag, the MJCF's rotor_i / thrust_i, telemetry f1..f4): every built-in vehicle numbers its
  // rotors as RotorPy's vehicles do (crazyflie_params.py's r1..r4), so that a motor-level
  // controller written for RotorPy flies them: 0 front-left, 1 front-right, 2 back-right,
  // 3 back-left (clockwise seen from above).
  std::array<Vec3, kNumRotors> rotor_positions_B = {Vec3(0.035, 0.035, 0), Vec3(0.035, -0.035, 0),
                                                    Vec3(-0.035, -0.035, 0),
                                                    Vec3(-0.035, 0.035, 0)};

  // Sign of each rotor's reaction (yaw) moment on the body about body z, as RotorPy's
  // rotor_directions: +1 for a rotor that spins clockwise seen from above. Diagonal rotors
  // share a sign, so equal thrusts give no yaw moment. RotorPy's 1, -1, 1, -1: front-left and
  // back-right clockwise, front-right and back-left counter-clockwise.
  std::array<int, kNumRotors> rotor_directions = {+1, -1, +1, -1};

  // Rotor limits [N]: thrust-to-weight about 2 (4 x 0.4 N / (0.08 kg x 9.81)).
  double min_rotor_thrust = 0.0;
  double max_rotor_thrust = 0.4;

  // Thrust per squared rotor speed [N / (rad/s)^2] (RotorPy's k_eta): only for rotor speeds
  // (commands and reports); the simulation works in thrust. A Tello's 3-inch propeller: the
  // Crazyflie's 2.3e-8 scaled by the propeller diameter to the 4th power, (76 / 46 mm)^4,
  // which puts the 0.4 N limit at about 1530 rad/s (14,600 rpm).
  double thrust_coefficient = 1.7e-7;

  // Reaction (yaw) moment per newton of thrust [N m / N = m] (RotorPy's k_m / k_eta). An
  // estimate for 3-inch-class propellers; it only sets the yaw authority, which the controller
  // ranks last.
  double yaw_moment_per_thrust = 0.006;

  // First-order motor lag of the thrust [s]. RotorS uses 1/80 s spinning up and 1/40 s down;
  // MuJoCo 2.2's filter actuator has one time constant, so 20 ms sits between the two.
  double motor_time_constant = 0.020;

  // Rotor speed noise [rad/s]: N(0, sigma^2) added to each rotor's produced speed once per
  // control period (RotorPy's motor_noise_std, which it adds once per simulation step, the
  // period its controller runs at); the motor lag then carries it. 0: the rotors produce what
  // is commanded.
  double motor_noise = 0.0;

  // Top speed [m/s]: DJI's specification for the Tello, 8 m/s. Trajectories stay below it.
  double max_speed = 8.0;

  // Body (parasitic) drag, quadratic in the airspeed, per body axis [N / (m/s)^2] (RotorPy's
  // c_Dx, c_Dy, c_Dz): F_B = -c |v| v with v the airspeed in the body frame. 0.5 rho Cd A with
  // rho = 1.2 kg/m^3, Cd = 1 (a bluff box) and the Tello's faces: 98 x 41 mm seen from the
  // front, 92.5 x 41 mm from the side, 98 x 92.5 mm from above. An estimate: at 8 m/s it costs
  // 0.15 N, a fifth of the weight.
  Vec3 body_drag = Vec3(2.4e-3, 2.3e-3, 5.4e-3);

  // Rotor (induced) drag per newton of the rotor's thrust and per m/s of its airspeed, per body
  // axis [N / (N m/s) = s/m]: F_B = -T_i diag(k) v_i, with v_i the airspeed at rotor i
  // (Faessler, Franchi and Scaramuzza 2018: drag linear in the speed, proportional to thrust;
  // they identified 0.26-0.28 1/s mass-normalised at hover, 0.027 s/m per newton of thrust).
  // Taken for this size as well (an estimate); none along the rotor axis.
  Vec3 rotor_drag = Vec3(0.027, 0.027, 0.0);

  // Collision body: a box of these full sides [m], centred at the body origin. The Tello's
  // 98 x 92.5 x 41 mm rounded up to cover the guards.
  Vec3 collision_size = Vec3(0.10, 0.10, 0.05);

  // Visual only [m]: propeller radius and guard radius (the guards stay within the 0.10 m
  // collision box up to a few millimetres).
  double propeller_radius = 0.016;
  double guard_radius = 0.0175;

  // The numbers a scenario's [vehicle] sets (common/schema.h); the rotors' positions and
  // directions are arrays of four, read by the scenario.
  void Describe(Archive& a);
  // Throws std::invalid_argument naming the field and value when a value is not physical.
  void Validate() const;

  double MinRotorThrust() const { return min_rotor_thrust; }
  double MaxRotorThrust() const { return max_rotor_thrust; }
  // Thrust of each rotor that holds a hover [N].
  double HoverThrustPerRotor() const { return mass * kGravity / kNumRotors; }
  // Rotor speed for a thrust and back [rad/s, N], through thrust_coefficient.
  double RotorSpeedFor(double thrust) const;
  double ThrustAtSpeed(double speed) const { return thrust_coefficient * speed * speed; }
  // The largest distance of a rotor centre from the body z axis [m] (for visuals).
  double ArmLength() const;
};

// The built-in vehicles by name ("tello", "crazyflie"), or nothing.
std::optional<QuadParams> BuiltinVehicle(const std::string& kind);
std::vector<std::string> BuiltinVehicleNames();

// The vehicle's drag per unit mass, lumped in the world frame for planning and feed-forward:
// rotor drag at hover thrust (k g) across the rotor disc, body drag (c / m), body axes taken as
// the world's (near level flight).
DragModel LumpedDrag(const QuadParams& params);

// Rotor centre in the body frame [m].
Vec3 RotorPosition_B(const QuadParams& params, int rotor);

// Yaw moment on the body per newton of this rotor's thrust [m]:
// rotor_directions[rotor] * yaw_moment_per_thrust.
double RotorYawMomentPerThrust(const QuadParams& params, int rotor);

// Allocation matrix A: [total thrust N; roll, pitch, yaw moments N m (body frame)] = A * f,
// where f holds the four rotor thrusts [N]. Moments are r_i x (0, 0, f_i) plus the reaction.
Mat4 AllocationMatrix(const QuadParams& params);

}  // namespace aerobox
