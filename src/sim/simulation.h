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

// One vehicle of a MuJoCo world (Simulation owns the world and one per vehicle): its body,
// actuators and motor lag, found by the vehicle's name (model_names::Of). Step sets this
// vehicle's commands and advances the whole world (the others fly on their last commands);
// a loop over several vehicles sets each one's commands (SetCommands) and steps the world once
// (Simulation::StepWorld). ResetData and ScaleVehicle reset the whole world's data.
class MujocoVehicle : public VehiclePhysics {
 public:
  // Throws InputError (naming `source`) when the model lacks the vehicle's body, joint or
  // rotor actuators.
  // `resets` counts the resets of the world's data, shared by its vehicles.
  MujocoVehicle(mjModel* model, mjData* data, std::string name, const std::string& source,
                std::shared_ptr<long> resets);

  const std::string& name() const { return name_; }
  int body_id() const { return body_id_; }

  // The rotor commands [N] the next world step flies (clamped by the actuators' ctrlrange).
  void SetCommands(const Vec4& thrust_commands);

  void Step(const Vec4& thrust_commands) override;
  void SetExternalWrench(const Vec3& force_W, const Vec3& torque_W) override;
  Vec4 RotorThrusts() const override;
  void SetRotorThrusts(const Vec4& thrusts) override;
  void SetProducedThrusts(const Vec4& thrusts) override;
  void ResetData() override;
  void ScaleVehicle(const VehicleScaling& scaling) override;
  State VehicleState() const override;
  void SetVehicleState(const State& state) override;
  Vec3 LinearAcceleration_W() const override;
  Vec3 AngularAcceleration_B() const override;
  std::string TakeNewWarnings() override;
  // Contacts of this vehicle with anything else; another vehicle is named by its name (its
  // elements' prefix), a map's geom by the geom's.
  std::vector<VehicleContact> VehicleContacts() const override;
  bool VehicleTouches() const override;
  double time() const override { return data_->time; }
  double timestep() const override { return model_->opt.timestep; }

 private:
  mjModel* model_;
  mjData* data_;
  std::string name_;
  int body_id_ = -1;
  int qpos_adr_ = -1;  // the free joint's position (3) and quaternion (4)
  int qvel_adr_ = -1;  // its linear velocity in the world (3), angular in the body (3)
  std::array<int, 4> actuator_ids_{};
  std::array<int, 4> act_adr_{};                 // each rotor's motor-lag state in mjData::act
  std::array<int, mjNWARNING> warnings_seen_{};  // mjData::warning[i].number already reported
  std::shared_ptr<long> resets_;                 // the world's resets ...
  long resets_seen_ = 0;                         // ... as of warnings_seen_
  // the vehicle's values as made, which ScaleVehicle scales
  struct Made {
    double mass = 0.0;
    Vec3 inertia = Vec3::Zero();
    Vec4 gain = Vec4::Zero(), yaw = Vec4::Zero(), lag = Vec4::Zero(), limit = Vec4::Zero();
  } made_;
};

class Simulation : public VehiclePhysics {
 public:
  // Loads MJCF text; `source` names it in messages. `vehicles` names the world's vehicles
  // (model_names::Of); empty: the scene's own, found by their bodies (the lone vehicle's plain
  // "quad", or each "<name>/quad" in the model's order). Throws InputError with MuJoCo's message
  // when it does not load, or when it lacks a vehicle's body, rotor actuators or joint.
  static Simulation FromXml(const std::string& xml, const std::string& source,
                            const std::vector<std::string>& vehicles = {});
  // Loads an MJCF file (it may include meshes etc. relative to itself).
  static Simulation FromFile(const std::string& path);

  // The world's vehicles, in the order they were named; this Simulation's own VehiclePhysics
  // methods act on the first.
  int vehicle_count() const { return static_cast<int>(vehicles_.size()); }
  MujocoVehicle& vehicle(int i) { return *vehicles_.at(static_cast<size_t>(i)); }
  const MujocoVehicle& vehicle(int i) const { return *vehicles_.at(static_cast<size_t>(i)); }
  // Advances the world one time step, every vehicle on the commands last set (SetCommands).
  void StepWorld();

  // Applies the four rotor thrust commands [N] (rotor order in vehicle/quad_params.h) and
  // advances one time step. Commands outside [0, max] are clamped by the actuators' ctrlrange;
  // the produced thrust follows the command with the motor lag.
  void Step(const Vec4& thrust_commands) override { first().Step(thrust_commands); }

  // A force [N] and torque [N m] in the world frame on the vehicle at its centre of mass (wind
  // and drag), applied by every Step until set again (MuJoCo's xfrc_applied).
  void SetExternalWrench(const Vec3& force_W, const Vec3& torque_W) override {
    first().SetExternalWrench(force_W, torque_W);
  }

  // Thrust each rotor produces now [N]: the motor-lag state.
  Vec4 RotorThrusts() const override { return first().RotorThrusts(); }
  // Sets the produced thrusts and the commands (e.g. start in hover without spin-up).
  void SetRotorThrusts(const Vec4& thrusts) override { first().SetRotorThrusts(thrusts); }
  // Sets the produced thrusts only (the motor-lag state; e.g. rotor noise): the next Step
  // starts from them.
  void SetProducedThrusts(const Vec4& thrusts) override { first().SetProducedThrusts(thrusts); }

  // A new simulation of a copy of this one's model, with fresh data (as loaded): many worlds of
  // one scene without parsing it again.
  Simulation Clone() const;
  // Back to the data as loaded: time 0, the model's initial state, no contacts, no warnings.
  void ResetData() override { first().ResetData(); }

  // Sets the vehicle's physics to the made values times `scaling` (not cumulative), and
  // resets the data as ResetData does (MuJoCo's constants follow the new mass: mj_setConst).
  void ScaleVehicle(const VehicleScaling& scaling) override { first().ScaleVehicle(scaling); }

  State VehicleState() const override { return first().VehicleState(); }
  // Places the vehicle and recomputes derived quantities (mj_forward).
  void SetVehicleState(const State& state) override { first().SetVehicleState(state); }

  // Accelerations from the last step or SetVehicleState: linear of the body origin in the
  // world frame [m/s^2] and angular in the body frame [rad/s^2].
  Vec3 LinearAcceleration_W() const override { return first().LinearAcceleration_W(); }
  Vec3 AngularAcceleration_B() const override { return first().AngularAcceleration_B(); }

  // MuJoCo's warnings (an engine reset after a bad acceleration, a full contact buffer, ...)
  // raised by this simulation since the last call, in MuJoCo's words; "" when there were none.
  // MuJoCo counts them in mjData; a flight that meets one cannot be trusted.
  std::string TakeNewWarnings() override { return first().TakeNewWarnings(); }

  // Contacts the vehicle has in the current state.
  std::vector<VehicleContact> VehicleContacts() const override { return first().VehicleContacts(); }
  // Whether it has any (VehicleContacts without their names: cheap enough for every step).
  bool VehicleTouches() const override { return first().VehicleTouches(); }

  double time() const override { return data_->time; }
  double timestep() const override { return model_->opt.timestep; }
  const mjModel* model() const { return model_.get(); }
  const mjData* data() const { return data_.get(); }
  // For renderers only: MuJoCo's visual API takes non-const pointers (mjv_updateScene), and the
  // off-screen settings live in the model. Nothing may change the physics through these.
  mjModel* mutable_model() { return model_.get(); }
  mjData* mutable_data() { return data_.get(); }

 private:
  Simulation(MjModelPtr model, const std::string& source, const std::vector<std::string>& vehicles);
  MujocoVehicle& first() { return *vehicles_.front(); }
  const MujocoVehicle& first() const { return *vehicles_.front(); }

  MjModelPtr model_;
  MjDataPtr data_;
  std::vector<std::unique_ptr<MujocoVehicle>> vehicles_;  // on the heap: a move keeps them
};

}  // namespace aerobox
