// The vehicle as a lone rigid body in a world of boxes and a floor, integrated without MuJoCo
// exactly as MuJoCo 2.2 integrates the model aerobox writes for it: the second physics of the
// learning environments (EnvParams::backend "rigid"), for speed where nothing but the vehicle
// moves. One step, from the state before it:
//   contacts of the state (the hull box against the floor plane and the map's boxes, touching
//   counts: MuJoCo's zero margin); c = the commands clamped to the rotors' range;
//   f_i = gain_i act_i (the produced thrust, the motor lag's state before the step);
//   a = (R e_z sum f_i + F_ext) / m + g;
//   alpha = I^-1 (sum f_i (r_i x e_z + k_i e_z) + R^T T_ext - w x I w)   (body axes);
//   act_i += dt (c_i - act_i) / tau_i;  v += dt a;  w += dt alpha;
//   p += dt v;  q = q (x) exp(w dt / 2)   (semi-implicit Euler, MuJoCo's mj_Euler).
// No contact forces: a touch ends an episode (the environments stop there, as on MuJoCo).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "common/types.h"
#include "sim/vehicle_physics.h"

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

class RigidBody : public VehiclePhysics {
 public:
  explicit RigidBody(RigidModel model);

  double time() const override { return time_; }
  double timestep() const override { return model_.timestep; }
  void Step(const Vec4& thrust_commands) override;
  void SetExternalWrench(const Vec3& force_W, const Vec3& torque_W) override;
  Vec4 RotorThrusts() const override;
  void SetRotorThrusts(const Vec4& thrusts) override;
  void SetProducedThrusts(const Vec4& thrusts) override { act_ = thrusts; }
  void ResetData() override;
  void ScaleVehicle(const VehicleScaling& scaling) override;
  State VehicleState() const override;
  void SetVehicleState(const State& state) override;
  Vec3 LinearAcceleration_W() const override { return acc_W_; }
  Vec3 AngularAcceleration_B() const override { return alpha_B_; }
  std::string TakeNewWarnings() override;
  std::vector<VehicleContact> VehicleContacts() const override;
  bool VehicleTouches() const override { return touches_; }

  const RigidModel& model() const { return model_; }

 private:
  // MuJoCo's forward pass at the current state: contacts, the clamped commands, accelerations.
  void Forward();
  // A state or an acceleration that is not finite (or beyond 1e10): MuJoCo's reset.
  void Warn(const std::string& what);
  void AddWarning(const std::string& what);
  // [m] from the hull's lowest corner down to the floor (negative: below it), the hull at p
  // with attitude R.
  double FloorDistance(const Vec3& p, const Mat3& R) const;
  // [m] how deep the hull (at p, attitude R) and `box` overlap along the axis they overlap
  // least (a separating-axis test): >= 0 when they touch; negative when apart (then only some
  // separation, not the distance).
  double Overlap(const Aabb& box, const Vec3& p, const Mat3& R) const;

  RigidModel made_;   // as read
  RigidModel model_;  // as scaled
  double time_ = 0.0;
  Vec3 p_W_, v_W_, w_B_;
  Vec4 q_ = Vec4(1, 0, 0, 0);  // w, x, y, z (MuJoCo's order and arithmetic)
  Vec4 act_ = Vec4::Zero();    // the motor lag's state
  Vec4 ctrl_ = Vec4::Zero();   // the last commands
  Vec3 force_W_ = Vec3::Zero(), torque_W_ = Vec3::Zero();
  Vec4 clamped_ = Vec4::Zero();
  Vec3 acc_W_ = Vec3::Zero(), alpha_B_ = Vec3::Zero();
  bool touches_ = false;
  Vec3 contact_p_W_ = Vec3::Zero();  // the pose the contacts were found in
  Mat3 contact_R_ = Mat3::Identity();
  std::string warnings_;
};

}  // namespace aerobox
