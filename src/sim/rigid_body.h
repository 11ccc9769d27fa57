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
// The state lives in a RigidBatch (sim/rigid_batch.h): a RigidBody is one world of it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "common/types.h"
#include "sim/rigid_batch.h"
#include "sim/rigid_model.h"
#include "sim/vehicle_physics.h"

namespace aerobox {

class RigidBody : public VehiclePhysics {
 public:
  // A world of its own.
  explicit RigidBody(RigidModel model);
  // World `index` of `batch`, which outlives it.
  RigidBody(RigidBatch* batch, int index);

  double time() const override { return batch_->time(i_); }
  double timestep() const override { return batch_->model().timestep; }
  void Step(const Vec4& thrust_commands) override;
  void SetExternalWrench(const Vec3& force_W, const Vec3& torque_W) override {
    batch_->SetExternalWrench(i_, force_W, torque_W);
  }
  Vec4 RotorThrusts() const override { return batch_->RotorThrusts(i_); }
  void SetRotorThrusts(const Vec4& thrusts) override { batch_->SetRotorThrusts(i_, thrusts); }
  void SetProducedThrusts(const Vec4& thrusts) override { batch_->SetProducedThrusts(i_, thrusts); }
  void ResetData() override { batch_->ResetData(i_); }
  void ScaleVehicle(const VehicleScaling& scaling) override { batch_->ScaleVehicle(i_, scaling); }
  State VehicleState() const override { return batch_->VehicleState(i_); }
  void SetVehicleState(const State& state) override { batch_->SetVehicleState(i_, state); }
  Vec3 LinearAcceleration_W() const override { return batch_->LinearAcceleration_W(i_); }
  Vec3 AngularAcceleration_B() const override { return batch_->AngularAcceleration_B(i_); }
  std::string TakeNewWarnings() override { return batch_->TakeNewWarnings(i_); }
  std::vector<VehicleContact> VehicleContacts() const override {
    return batch_->VehicleContacts(i_);
  }
  bool VehicleTouches() const override { return batch_->VehicleTouches(i_); }

  RigidBatch& batch() const { return *batch_; }
  int index() const { return i_; }

 private:
  std::unique_ptr<RigidBatch> own_;  // a world of its own: a batch of one
  RigidBatch* batch_;
  int i_;
};

}  // namespace aerobox
