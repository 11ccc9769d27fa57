// Owns one MuJoCo model and its data: loads an aerobox scene, steps it with four rotor thrust
// commands and reports the vehicle's state and contacts in our conventions.
#pragma once

#include <mujoco/mujoco.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "common/state.h"
#include "common/types.h"
#include "sim/vehicle_physics.h"

namespace aerobox {

struct MjModelDeleter {
  void operator()(mjModel* model) const { mj_deleteModel(model); }
};
struct MjDataDeleter {
  void operator()(mjData* data) const { mj_deleteData(data); }
};
using MjModelPtr = std::unique_ptr<mjModel, MjModelDeleter>;
using MjDataPtr = std::unique_ptr<mjData, MjDataDeleter>;

class Simulation : public VehiclePhysics {
 public:
  // Loads MJCF text; `source` names it in messages. Throws InputError with MuJoCo's message
  // when it does not load, or when it lacks the vehicle's body, rotor actuators or joint.
  static Simulation FromXml(const std::string& xml, const std::string& source);
  // Loads an MJCF file (it may include meshes etc. relative to itself).
  static Simulation FromFile(const std::string& path);

  // Applies the four rotor thrust commands [N] (rotor order in vehicle/quad_params.h) and
  // advances one time step. Commands outside [0, max] are clamped by the actuators' ctrlrange;
  // the produced thrust follows the command with the motor lag.
  void Step(const Vec4& thrust_commands) override;

  // A force [N] and torque [N m] in the world frame on the vehicle at its centre of mass (wind
  // and drag), applied by every Step until set again (MuJoCo's xfrc_applied).
  void SetExternalWrench(const Vec3& force_W, const Vec3& torque_W) override;

  // Thrust each rotor produces now [N]: the motor-lag state.
  Vec4 RotorThrusts() const override;
  // Sets the produced thrusts and the commands (e.g. start in hover without spin-up).
  void SetRotorThrusts(const Vec4& thrusts) override;
  // Sets the produced thrusts only (the motor-lag state; e.g. rotor noise): the next Step
  // starts from them.
  void SetProducedThrusts(const Vec4& thrusts) override;

  // A new simulation of a copy of this one's model, with fresh data (as loaded): many worlds of
  // one scene without parsing it again.
  Simulation Clone() const;
  // Back to the data as loaded: time 0, the model's initial state, no contacts, no warnings.
  void ResetData() override;

  // Sets the vehicle's physics to the made values times `scaling` (not cumulative), and
  // resets the data as ResetData does (MuJoCo's constants follow the new mass: mj_setConst).
  void ScaleVehicle(const VehicleScaling& scaling) override;

  State VehicleState() const override;
  // Places the vehicle and recomputes derived quantities (mj_forward).
  void SetVehicleState(const State& state) override;

  // Accelerations from the last step or SetVehicleState: linear of the body origin in the
  // world frame [m/s^2] and angular in the body frame [rad/s^2].
  Vec3 LinearAcceleration_W() const override;
  Vec3 AngularAcceleration_B() const override;

  // MuJoCo's warnings (an engine reset after a bad acceleration, a full contact buffer, ...)
  // raised by this simulation since the last call, in MuJoCo's words; "" when there were none.
  // MuJoCo counts them in mjData; a flight that meets one cannot be trusted.
  std::string TakeNewWarnings() override;

  // Contacts the vehicle has in the current state.
  std::vector<VehicleContact> VehicleContacts() const override;
  // Whether it has any (VehicleContacts without their names: cheap enough for every step).
  bool VehicleTouches() const override;

  double time() const override { return data_->time; }
  double timestep() const override { return model_->opt.timestep; }
  const mjModel* model() const { return model_.get(); }
  const mjData* data() const { return data_.get(); }
  // For renderers only: MuJoCo's visual API takes non-const pointers (mjv_updateScene), and the
  // off-screen settings live in the model. Nothing may change the physics through these.
  mjModel* mutable_model() { return model_.get(); }
  mjData* mutable_data() { return data_.get(); }

 private:
  Simulation(MjModelPtr model, const std::string& source);

  MjModelPtr model_;
  MjDataPtr data_;
  int body_id_ = -1;
  int qpos_adr_ = -1;  // the free joint's position (3) and quaternion (4)
  int qvel_adr_ = -1;  // its linear velocity in the world (3), angular in the body (3)
  std::array<int, 4> actuator_ids_{};
  std::array<int, 4> act_adr_{};                 // each rotor's motor-lag state in mjData::act
  std::array<int, mjNWARNING> warnings_seen_{};  // mjData::warning[i].number already reported
  // the vehicle's values as made, which ScaleVehicle scales
  struct Made {
    double mass = 0.0;
    Vec3 inertia = Vec3::Zero();
    Vec4 gain = Vec4::Zero(), yaw = Vec4::Zero(), lag = Vec4::Zero(), limit = Vec4::Zero();
  } made_;
};

}  // namespace aerobox
