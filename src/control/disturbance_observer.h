// The external force on the vehicle, estimated in flight (a disturbance observer): Newton's law
// with the measured acceleration and the rotors' thrust leaves what else pushes the vehicle,
// F = m a - R (sum of the rotor thrusts) e_z + m g e_z [N, world] (wind and drag, a payload's
// weight, a tether), filtered to the first order. Any controller can fly with it
// (WithDisturbanceObserver): the estimate divided by the mass is taken off the acceleration the
// setpoint asks, so the controller's feedback no longer has to hold the force off. With sensors
// on, the acceleration is the IMU's (its specific force less the estimated bias, turned by the
// estimated attitude, less gravity), else the physics' own; the thrusts are the rotors' (what a
// real vehicle gets from its rotor speeds and thrust coefficient).
#pragma once

#include <memory>

#include "common/schema.h"
#include "control/controller.h"

namespace aerobox {

// What else pushes the vehicle [N, world], by Newton's law: its mass [kg] times its measured
// acceleration a_W [m/s^2] (gravity not included), less the rotors' thrust [N, world], plus its
// weight. INDI reports it too (control/indi_control.h).
inline Vec3 ExternalForce(double mass, const Vec3& a_W, const Vec3& thrust_W) {
  return mass * a_W - thrust_W + Vec3(0, 0, mass * kGravity);
}

struct DisturbanceObserverParams {
  bool enabled = false;
  double time_constant = 0.05;  // [s] of the first-order filter: 95 % of a step in 3 of them

  void Describe(Archive& a);  // [controller] observer, observer_time_constant
};

class DisturbanceObserver {
 public:
  DisturbanceObserver(double time_constant, double mass);
  // One update `dt` [s] after the last, with the vehicle at attitude `q_WB`.
  void Update(double dt, const Surroundings& now, const Quat& q_WB);
  const Vec3& force_W() const { return force_W_; }  // [N]

 private:
  double time_constant_, mass_;
  bool started_ = false;
  Vec3 force_W_ = Vec3::Zero();
};

// `inner` flown with the observer's estimate fed forward (see above); its report gains the
// columns fext_x, fext_y, fext_z [N]. `period` [s]: how often the controller runs.
std::unique_ptr<Controller> WithDisturbanceObserver(std::unique_ptr<Controller> inner,
                                                    const DisturbanceObserverParams& params,
                                                    double mass, double period);

}  // namespace aerobox
