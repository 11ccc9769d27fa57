// The rigid bodies of N worlds of one scene (sim/rigid_body.h says the physics), kept as a
// structure of arrays (one array across the worlds per state component, per command and per
// varied vehicle parameter) and stepped together: each phase of a step is one loop over a range
// of worlds, which the compiler vectorises across worlds; a batch of environments steps its
// threads' blocks of worlds in one call each. World i gives exactly what a lone rigid body gives
// (a RigidBody is a batch of one, or a view of one world of a batch), whatever the range it is
// stepped in.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/state.h"
#include "common/types.h"
#include "sim/rigid_model.h"
#include "sim/vehicle_physics.h"

namespace aerobox {

class RigidBatch {
 public:
  // `worlds` >= 1 copies of `model`'s vehicle, each in its initial state.
  RigidBatch(RigidModel model, int worlds);

  int size() const { return size_; }
  const RigidModel& model() const { return model_; }  // as made (unscaled)

  // World i's physics, each as VehiclePhysics says (sim/vehicle_physics.h); 0 <= i < size().
  double time(int i) const { return At(kTime, i); }
  // The four rotor thrust commands [N] the next Step flies.
  void SetCommands(int i, const Vec4& thrust_commands) { Set4(kCtrl, i, thrust_commands); }
  void SetExternalWrench(int i, const Vec3& force_W, const Vec3& torque_W);
  Vec4 RotorThrusts(int i) const { return Get4(kAct, i); }
  void SetRotorThrusts(int i, const Vec4& thrusts);
  void SetProducedThrusts(int i, const Vec4& thrusts) { Set4(kAct, i, thrusts); }
  void ResetData(int i);
  void ScaleVehicle(int i, const VehicleScaling& scaling);
  State VehicleState(int i) const;
  void SetVehicleState(int i, const State& state);
  Vec3 LinearAcceleration_W(int i) const { return Get3(kAcc, i); }
  Vec3 AngularAcceleration_B(int i) const { return Get3(kAlpha, i); }
  std::string TakeNewWarnings(int i);
  std::vector<VehicleContact> VehicleContacts(int i) const;
  bool VehicleTouches(int i) const { return At(kTouches, i) != 0.0; }

  // One physics step of the worlds [begin, end), each with its commands (SetCommands). Ranges
  // that do not overlap may be stepped in different threads at once.
  void Step(int begin, int end);

 private:
  // The columns: one array of size() values each, the first of a vector's components named.
  enum Column : int {
    kP = 0,                     // [m] position, world (3)
    kQ = kP + 3,                // attitude quaternion w, x, y, z (4)
    kV = kQ + 4,                // [m/s] velocity, world (3)
    kW = kV + 3,                // [rad/s] angular velocity, body (3)
    kAct = kW + 3,              // [N] the motor lag's states: the produced thrusts (4)
    kCtrl = kAct + 4,           // [N] the commands (4)
    kClamped = kCtrl + 4,       // [N] the commands clamped to the rotors' range (4)
    kForce = kClamped + 4,      // [N] external force, world (3)
    kTorque = kForce + 3,       // [N m] external torque, world (3)
    kAcc = kTorque + 3,         // [m/s^2] linear acceleration, world (3)
    kAlpha = kAcc + 3,          // [rad/s^2] angular acceleration, body (3)
    kContactP = kAlpha + 3,     // the pose the contacts were found in (3 + 4)
    kContactQ = kContactP + 3,  //
    kTime = kContactQ + 4,      // [s]
    kMass = kTime + 1,          // the vehicle as scaled: [kg]
    kInertia = kMass + 1,       // [kg m^2] (3)
    kGain = kInertia + 3,       // (4)
    kYawMoment = kGain + 4,     // [m] (4)
    kLag = kYawMoment + 4,      // [s] (4)
    kCommandMax = kLag + 4,     // [N] (4)
    kFlags = kCommandMax + 4,   // scratch of a step: what a check found, per world
    kTouches = kFlags + 1,      // 1 when the vehicle touches anything, else 0
    kColumns = kTouches + 1
  };

  double& At(int column, int i) { return data_[static_cast<size_t>(column) * stride_ + i]; }
  double At(int column, int i) const { return data_[static_cast<size_t>(column) * stride_ + i]; }
  Vec3 Get3(int column, int i) const;
  Vec4 Get4(int column, int i) const;
  void Set3(int column, int i, const Vec3& v);
  void Set4(int column, int i, const Vec4& v);

  // MuJoCo's forward pass for [begin, end): the quaternion normalised, the contacts, the clamped
  // commands, the accelerations.
  void Forward(int begin, int end);
  // The hull against the map's boxes, for the worlds of [begin, end) not yet touching.
  void TouchBoxes(int begin, int end);
  // MuJoCo's checks before the forward pass (a state not finite resets the world; commands not
  // finite become zero) and after it (an acceleration not finite resets the world).
  void CheckBefore(int begin, int end);
  void CheckAfter(int begin, int end);
  // Semi-implicit Euler in mj_Euler's order: the motor lag, the velocities, the positions, the
  // attitude (MuJoCo's mju_quatIntegrate).
  void Integrate(int begin, int end);
  void AddWarning(int i, const std::string& what);
  // A state or an acceleration that is not finite (or beyond 1e10): MuJoCo's reset, warned.
  void Warn(int i, const std::string& what);

  RigidModel model_;
  int size_;
  size_t stride_;             // between columns: size() rounded up to an odd number of cache lines
  std::vector<double> data_;  // kColumns x stride_
  std::vector<std::string> warnings_;
};

}  // namespace aerobox
