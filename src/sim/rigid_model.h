// What the rigid body (sim/rigid_body.h, sim/rigid_batch.h) needs of a scene: its vehicle's
// mass, inertia, rotors and hull, the world's floor and boxes, read from MuJoCo's compiled model,
// with every assumption the rigid body makes about that model checked.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "common/types.h"

namespace aerobox {

class Simulation;

// What the rigid body needs of a scene, read from MuJoCo's compiled model of it.
struct RigidModel {
  double timestep = 0.001;           // [s]
  Vec3 gravity = Vec3(0, 0, -9.81);  // [m/s^2]
  double mass = 0.0;                 // [kg]
  Vec3 inertia = Vec3::Zero();       // [kg m^2] principal, along the body axes
  std::array<Vec3, 4> rotor_B{};     // [m] each rotor's position on the body
  Vec4 gain = Vec4::Ones();          // produced thrust per unit of motor state
  Vec4 yaw_moment = Vec4::Zero();    // [m] reaction moment per newton (signed)
  Vec4 lag = Vec4::Constant(0.05);   // [s] motor time constants
  Vec4 command_min = Vec4::Zero();   // [N]
  Vec4 command_max = Vec4::Ones();   // [N]
  Vec3 hull_half = Vec3::Zero();     // [m] the collision box's half sizes, at the centre
  bool has_floor = false;
  double floor_z = 0.0;                // [m]
  std::vector<Aabb> boxes;             // the world's boxes
  std::vector<std::string> box_names;  // their geoms' names
  Vec3 initial_p_W = Vec3::Zero();     // [m] the state ResetData returns to
  Quat initial_q_WB = Quat::Identity();

  // From `sim`'s model as loaded. Throws std::invalid_argument naming the element when the
  // model is one the rigid body does not reproduce (another integrator, fluid forces, joint
  // damping, a centre of mass off the body's origin, a geom other than a box or a plane, a
  // rotated box, ...).
  static RigidModel Of(const Simulation& sim);
};

}  // namespace aerobox
