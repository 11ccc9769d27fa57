#include "envs/env_params.h"

#include <cmath>
#include <stdexcept>

namespace aerobox {

void EnvParams::Describe(Archive& a) {
  a.Choice({"task", "", "hover: reach and hold the target from a random start"}, &task, {"hover"});
  a.Choice({"vehicle", "", "a built-in vehicle"}, &vehicle, {"crazyflie", "tello"});
  a.Choice({"action", "", "what the action commands, each component in [-1, 1]"}, &action,
           {"thrusts", "ctbm", "ctbr", "ctatt"});
  a.Choice({"attitude", "", "the attitude in the observation: R_WB row by row, or w, x, y, z"},
           &attitude, {"matrix", "quaternion"});
  a.Number({"control_rate", "Hz", "steps per second; must divide the 1000 Hz physics"},
           &control_rate, 1, 1000);
  a.Number({"episode_time", "s", "then the episode is truncated"}, &episode_time, 0.01, 3600);
  a.Vector({"target", "m", "the point to reach and hold (world ENU)"}, &target, -1e3, 1e3);
  a.Number({"start_radius", "m", "the start is uniform in this ball around the target"},
           &start_radius, 0, 100);
  a.Number({"start_speed", "m/s", "the start's speed at most, in a random direction"}, &start_speed,
           0, 20);
  a.Number({"start_tilt", "rad", "the start's tilt at most; its yaw is random"}, &start_tilt, 0,
           1.5);
  a.Number({"start_rate", "rad/s", "the start's body rate at most"}, &start_rate, 0, 20);
  a.Number({"bounds_radius", "m", "this far from the target, the episode terminates"},
           &bounds_radius, 0.1, 1e3);
  a.Number({"max_rate", "rad/s", "body rate at action +-1 (ctbr)"}, &max_rate, 0.1, 50);
  a.Number({"max_tilt", "rad", "roll and pitch at action +-1 (ctatt)"}, &max_tilt, 0.05, 1.5);
  a.Number({"reward_alive", "", "added every step"}, &reward_alive, 0, 1e3);
  a.Number({"reward_position", "1/m", "times the distance to the target, taken off"},
           &reward_position, 0, 1e3);
  a.Number({"reward_velocity", "s/m", "times the speed, taken off"}, &reward_velocity, 0, 1e3);
  a.Number({"reward_rate", "s/rad", "times the body rate's norm, taken off"}, &reward_rate, 0, 1e3);
  a.Number({"reward_action", "", "times the action's squared norm, taken off"}, &reward_action, 0,
           1e3);
}

void EnvParams::Validate() const {
  ValidateFields(*this, "env");
  const double steps = 1000.0 / control_rate;
  if (std::abs(steps - std::round(steps)) > 1e-9) {
    throw std::invalid_argument("env.control_rate " + std::to_string(control_rate) +
                                " Hz must divide the 1000 Hz physics (1000, 500, 250, 200, "
                                "100, 50 ...)");
  }
  if (target.z() - start_radius < 0.1) {
    throw std::invalid_argument(
        "env.target's height must exceed start_radius by 0.1 m: a start "
        "would be in the floor");
  }
}

QuadParams EnvParams::Vehicle() const { return *BuiltinVehicle(vehicle); }

std::vector<std::string> EnvParams::ObservationNames() const {
  std::vector<std::string> names = {"dx", "dy", "dz", "vx", "vy", "vz"};
  if (attitude == "matrix") {
    for (int r = 1; r <= 3; ++r) {
      for (int c = 1; c <= 3; ++c) names.push_back("R" + std::to_string(r) + std::to_string(c));
    }
  } else {
    names.insert(names.end(), {"qw", "qx", "qy", "qz"});
  }
  names.insert(names.end(), {"wx", "wy", "wz"});
  for (int i = 0; i < ActionSize(); ++i) names.push_back("a" + std::to_string(i));
  return names;
}

const std::vector<std::string>& RewardTermNames() {
  static const std::vector<std::string> kNames = {"alive", "position", "velocity", "rate",
                                                  "action"};
  return kNames;
}

}  // namespace aerobox
