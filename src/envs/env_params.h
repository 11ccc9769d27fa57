// The learning environments' parameters, through the schema (common/schema.h): the task, the
// vehicle, the action level and its scaling, the observation's attitude form, the episode, the
// random start and the reward's weights. Python's aerobox.envs takes them as keyword arguments.
#pragma once

#include <string>
#include <vector>

#include "common/schema.h"
#include "common/types.h"
#include "vehicle/quad_params.h"

namespace aerobox {

struct EnvParams {
  std::string task = "hover";         // reach and hold `target` from a random start
  std::string vehicle = "crazyflie";  // a built-in vehicle (vehicle/quad_params.h)
  // What the action commands, each component in [-1, 1] (docs/learning.md gives the scaling):
  // "thrusts" (four rotor thrusts), "ctbm" (collective thrust and body moments), "ctbr"
  // (collective thrust and body rates), "ctatt" (collective thrust and roll, pitch, yaw).
  // aerobox's inner loops run below it at the physics rate.
  std::string action = "ctbr";
  // The attitude in the observation: "matrix" (R_WB, row by row) or "quaternion" (w, x, y, z,
  // with w >= 0).
  std::string attitude = "matrix";
  double control_rate = 100.0;    // [Hz] one step(); must divide the 1000 Hz physics
  double episode_time = 10.0;     // [s] then truncated
  Vec3 target = Vec3(0, 0, 1.5);  // [m] world ENU
  double start_radius = 1.0;      // [m] the start is uniform in this ball around the target
  double start_speed = 0.5;       // [m/s] at most, in a random direction
  double start_tilt = 0.5;        // [rad] at most, about a random horizontal axis; yaw random
  double start_rate = 1.0;        // [rad/s] at most, in a random direction
  double bounds_radius = 3.0;     // [m] from the target: beyond, the episode terminates
  double max_rate = 10.0;         // [rad/s] of body rate at action +-1 ("ctbr")
  double max_tilt = 0.6;          // [rad] of roll and pitch at action +-1 ("ctatt")
  // the reward per step: alive - position |p - target| - velocity |v| - rate |w| - action |a|^2
  double reward_alive = 1.0;
  double reward_position = 1.0;  // [1/m]
  double reward_velocity = 0.1;  // [s/m]
  double reward_rate = 0.05;     // [s/rad]
  double reward_action = 0.01;

  void Describe(Archive& a);
  // Throws std::invalid_argument naming the field (ranges, a rate that does not divide the
  // physics, a known vehicle).
  void Validate() const;
  QuadParams Vehicle() const;  // the built-in vehicle `vehicle` names
  int ActionSize() const { return 4; }
  int AttitudeSize() const { return attitude == "matrix" ? 9 : 4; }
  // relative position (3), velocity (3), attitude, body rates (3), the last action
  int ObservationSize() const { return 9 + AttitudeSize() + ActionSize(); }
  // One name per observation component ("dx", "vx", "R11" or "qw", "wx", "a0", ...), in order.
  std::vector<std::string> ObservationNames() const;
};

// The names of the reward's terms, in the order EnvWorld reports them.
const std::vector<std::string>& RewardTermNames();

}  // namespace aerobox
