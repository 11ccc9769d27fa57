// The physics below one vehicle, as the flight loop and the learning environments use it: MuJoCo's
// (sim/simulation.h), or the rigid body alone, integrated as MuJoCo integrates it
// (sim/rigid_body.h). States in our conventions (common/state.h), thrusts per rotor in the
// order of vehicle/quad_params.h.
#pragma once

#include <string>
#include <vector>

#include "common/state.h"
#include "common/types.h"

namespace aerobox {

// A contact between the vehicle and anything else (an obstacle, the floor).
struct VehicleContact {
  std::string other_geom;  // name of the geom the vehicle touches ("" when unnamed)
  Vec3 position_W;         // contact point [m]
  double distance = 0.0;   // signed distance [m]; negative is penetration
};

// Changes to the vehicle's physics, as factors of the values the simulation was made with (1
// changes nothing): what domain randomisation varies from one episode to the next while the
// controller keeps the nominal vehicle. Per rotor: the thrust it produces per newton commanded,
// its reaction moment, its motor lag's time constant and its largest command.
struct VehicleScaling {
  double mass = 1.0;
  Vec3 inertia = Vec3::Ones();  // per principal axis
  Vec4 thrust = Vec4::Ones();
  Vec4 yaw_moment = Vec4::Ones();
  Vec4 motor_lag = Vec4::Ones();
  Vec4 rotor_limit = Vec4::Ones();
};

class VehiclePhysics {
 public:
  virtual ~VehiclePhysics() = default;

  virtual double time() const = 0;      // [s]
  virtual double timestep() const = 0;  // [s] of one Step

  // Applies the four rotor thrust commands [N] and advances one time step. Commands outside
  // [0, max] are clamped; the produced thrust follows the command with the motor lag.
  virtual void Step(const Vec4& thrust_commands) = 0;
  // A force [N] and torque [N m] in the world frame on the vehicle at its centre of mass (wind
  // and drag), applied by every Step until set again.
  virtual void SetExternalWrench(const Vec3& force_W, const Vec3& torque_W) = 0;

  // Thrust each rotor produces now [N]: the motor-lag state.
  virtual Vec4 RotorThrusts() const = 0;
  // Sets the produced thrusts and the commands (e.g. start in hover without spin-up).
  virtual void SetRotorThrusts(const Vec4& thrusts) = 0;
  // Sets the produced thrusts only (the motor-lag state; e.g. rotor noise).
  virtual void SetProducedThrusts(const Vec4& thrusts) = 0;

  // Back to the state as made: time 0, the initial state, no contacts, no warnings.
  virtual void ResetData() = 0;
  // The vehicle's physics: the made values times `scaling` (not cumulative); resets as
  // ResetData does.
  virtual void ScaleVehicle(const VehicleScaling& scaling) = 0;

  virtual State VehicleState() const = 0;
  // Places the vehicle; its accelerations and contacts follow the new state.
  virtual void SetVehicleState(const State& state) = 0;

  // Accelerations from the last step or SetVehicleState: linear of the centre of mass in the
  // world frame [m/s^2], angular in the body frame [rad/s^2].
  virtual Vec3 LinearAcceleration_W() const = 0;
  virtual Vec3 AngularAcceleration_B() const = 0;

  // Warnings (a state no longer finite, a bad command) raised since the last call, in words;
  // "" when there were none. A flight that meets one cannot be trusted.
  virtual std::string TakeNewWarnings() = 0;

  // Contacts of the vehicle in the state the last step started from (after SetVehicleState:
  // in that state); VehicleTouches is the same without names, cheap enough for every step.
  virtual std::vector<VehicleContact> VehicleContacts() const = 0;
  virtual bool VehicleTouches() const = 0;
};

}  // namespace aerobox
