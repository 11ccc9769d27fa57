// The controllers by name: the configuration a scenario's [controller] table sets, and the
// registry that makes a Controller of it ("cascade", "se3", "indi", and any a user registers).
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "common/registry.h"
#include "control/controller.h"
#include "control/disturbance_observer.h"
#include "control/inner_loops.h"
#include "control/position_control.h"
#include "control/se3_control.h"
#include "vehicle/quad_params.h"

namespace aerobox {

struct ControllerConfig {
  std::string kind = "cascade";  // a name in Controllers()
  // How often the controller runs [Hz]; it must divide the physics rate (1000 Hz). PX4 runs its
  // position loop at 250 Hz (every 4th physics step here); the inner loops run every step.
  double rate = 250.0;
  PositionControlParams cascade;  // kind "cascade": the position and velocity loops
  Se3Params se3;                  // kind "se3"
  InnerLoopParams inner;          // the attitude and rate loops below any command that needs them
  // Feed the vehicle's own drag (LumpedDrag, in still air) forward: the controller is given the
  // acceleration and jerk the thrust must produce, drag included. Scenarios turn it on with
  // [aero] unless [controller] drag_feedforward says otherwise.
  bool drag_feedforward = false;
  // Estimate the external force in flight and feed it forward (any kind; in place of the drag
  // feed-forward, whose force it measures too).
  DisturbanceObserverParams observer;
  // A registered controller's own parameters ([controller] keys beyond the built-ins'), with
  // the defaults it registered (Registry::Register); empty for the built-ins.
  PluginParameters params;

  // The built-in keys of [controller] but `kind` (common/schema.h); a registered controller's
  // own are in `params`. max_tilt is the cascade's (a scenario gives se3 the same).
  void Describe(Archive& a);
  // Throws std::invalid_argument naming the field.
  void Validate() const;
};

// Whether the controller `config` makes measures the vehicle's acceleration and rotor thrusts
// (indi, or any kind with the observer): from the IMU with sensors on, else the ground truth.
bool MeasuresAcceleration(const ControllerConfig& config);

using ControllerFactory =
    std::function<std::unique_ptr<Controller>(const ControllerConfig&, const QuadParams&)>;

// The registry, with the built-ins already in it.
Registry<ControllerFactory>& Controllers();

// A controller that flies `inner` with drag fed forward: each setpoint goes through
// CompensateDrag with `drag` (common/drag.h) in still air.
std::unique_ptr<Controller> WithDragFeedForward(std::unique_ptr<Controller> inner,
                                                const DragModel& drag);

// The controller `config.kind` names (with the disturbance observer, or else drag fed forward,
// when config asks; with its
// registered default parameters when config has none); throws std::invalid_argument for an
// unknown kind.
std::unique_ptr<Controller> MakeController(const ControllerConfig& config,
                                           const QuadParams& vehicle);

}  // namespace aerobox
