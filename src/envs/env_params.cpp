#include "envs/env_params.h"

#include <cmath>
#include <stdexcept>

#include "common/number_format.h"
#include "envs/env_task.h"

namespace aerobox {

void EnvParams::Describe(Archive& a) {
  a.Choice({"task", "",
            "hover: reach and hold the target; track: follow a random trajectory; "
            "navigate: reach a goal through a map of boxes"},
           &task, EnvTaskNames());
  a.Choice({"vehicle", "", "a built-in vehicle"}, &vehicle, {"crazyflie", "tello"});
  a.Choice({"backend", "",
            "the physics: MuJoCo, or the rigid body integrated as MuJoCo integrates it (faster; "
            "box contacts end the episode as on MuJoCo)"},
           &backend, {"mujoco", "rigid"});
  a.Choice({"action", "", "what the action commands, each component in [-1, 1]"}, &action,
           {"thrusts", "ctbm", "ctbr", "ctatt", "velocity"});
  a.Choice({"attitude", "", "the attitude in the observation: R_WB row by row, or w, x, y, z"},
           &attitude, {"matrix", "quaternion"});
  a.Number({"control_rate", "Hz", "steps per second; must divide physics_rate"}, &control_rate, 1,
           1000);
  a.Number({"physics_rate", "Hz", "physics steps per second (the inner loops run at it)"},
           &physics_rate, 50, 10000);
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
  a.Number({"max_speed", "m/s", "each velocity component at action +-1 (velocity)"}, &max_speed,
           0.1, 20);
  a.Choice({"track_shape", "", "track: the reference's shape, drawn per episode"}, &track_shape,
           {"both", "circle", "figure8"});
  a.Number({"track_size", "m", "track: the circle's radius, the figure-8's half-length, at most"},
           &track_size, 0.1, 100);
  a.Number({"track_speed", "m/s", "track: the reference's top speed, at most"}, &track_speed, 0.05,
           20);
  a.Integer({"track_points", "", "track: reference samples ahead in the observation"},
            &track_points, 0, 50);
  a.Number({"track_spacing", "s", "track: time between the samples ahead"}, &track_spacing, 0.001,
           10);
  a.Text({"map", "", "navigate: an aerobox map file (\"\": a random forest)"}, &map);
  a.Number({"forest_size", "m", "navigate: the random forest's square side"}, &forest_size, 2,
           1000);
  a.Number({"forest_height", "m", "navigate: the random forest's height"}, &forest_height, 1, 100);
  a.Integer({"forest_trees", "", "navigate: the random forest's trunks"}, &forest_trees, 0, 10000);
  a.Integer({"forest_seed", "", "navigate: the random forest's layout"}, &forest_seed, 0,
            1000000000);
  a.Number({"goal_distance", "m", "navigate: between the start and the goal, at least"},
           &goal_distance, 0, 1e3);
  a.Number({"arrival_radius", "m", "navigate: this near the goal, arrived"}, &arrival_radius, 0.01,
           100);
  a.Integer({"range_rays", "", "navigate: horizontal range rays (then one down, one up)"},
            &range_rays, 0, 360);
  a.Number({"range_max", "m", "navigate: a range ray's reach"}, &range_max, 0.1, 100);
  a.Integer({"depth_width", "px", "navigate: a depth image in the observation, its columns"},
            &depth_width, 0, 256);
  a.Integer({"depth_height", "px", "navigate: the depth image's rows"}, &depth_height, 0, 256);
  a.Number({"reward_alive", "", "added every step"}, &reward_alive, 0, 1e3);
  a.Number({"reward_position", "1/m", "times the distance to the target, taken off"},
           &reward_position, 0, 1e3);
  a.Number({"reward_velocity", "s/m", "times the speed, taken off"}, &reward_velocity, 0, 1e3);
  a.Number({"reward_rate", "s/rad", "times the body rate's norm, taken off"}, &reward_rate, 0, 1e3);
  a.Number({"reward_action", "", "times the action's squared norm, taken off"}, &reward_action, 0,
           1e3);
  a.Number({"reward_progress", "1/m", "navigate: times the step's approach to the goal"},
           &reward_progress, 0, 1e3);
  a.Number({"reward_arrival", "", "navigate: once, on arriving"}, &reward_arrival, 0, 1e6);
  // per episode, each a factor in [1 - f, 1 + f] (per rotor for the rotors')
  a.Number({"vary_mass", "", "per episode: the mass times 1 +- up to this"}, &vary_mass, 0, 0.5);
  a.Number({"vary_inertia", "", "per episode: the moments of inertia times 1 +- up to this"},
           &vary_inertia, 0, 0.5);
  a.Number({"vary_thrust", "", "per episode: each rotor's thrust per newton commanded, 1 +-"},
           &vary_thrust, 0, 0.5);
  a.Number({"vary_yaw_moment", "", "per episode: each rotor's reaction moment, 1 +-"},
           &vary_yaw_moment, 0, 0.5);
  a.Number({"vary_motor_lag", "", "per episode: each rotor's motor lag, 1 +-"}, &vary_motor_lag, 0,
           0.9);
  a.Number({"vary_rotor_limit", "", "per episode: each rotor's largest thrust command, 1 +-"},
           &vary_rotor_limit, 0, 0.5);
  a.Number({"wind_speed", "m/s", "per episode: a horizontal mean wind up to this, any direction"},
           &wind_speed, 0, 20);
  a.Number({"wind_turbulence", "m/s", "per episode: Dryden turbulence up to this intensity"},
           &wind_turbulence, 0, 10);
  a.Number({"gust_speed", "m/s", "per episode: one gust of a peak up to this, at a random time"},
           &gust_speed, 0, 20);
  a.Boolean({"drag", "", "body and rotor drag (on whenever there is wind)"}, &drag);
  a.Boolean({"sensors", "", "observe through aerobox's IMU, motion capture and estimator"},
            &sensors);
  a.Number({"vary_sensor_noise", "", "per episode: the sensors' noise times 1 +- up to this"},
           &vary_sensor_noise, 0, 0.9);
}

void EnvParams::Validate() const {
  ValidateFields(*this, "env");
  const double steps = physics_rate / control_rate;
  if (std::abs(steps - std::round(steps)) > 1e-9 || steps < 0.5) {
    throw std::invalid_argument("env.control_rate " + FormatNumber(control_rate) +
                                " Hz must divide env.physics_rate " + FormatNumber(physics_rate) +
                                " Hz (at 1000 Hz: 1000, 500, 250, 200, 100, 50 ...)");
  }
  if ((depth_width > 0) != (depth_height > 0)) {
    throw std::invalid_argument(
        "env.depth_height: a depth image needs both depth_width and depth_height (got " +
        std::to_string(depth_width) + " x " + std::to_string(depth_height) + " px)");
  }
  if (depth_width > 0 && task != "navigate") {
    throw std::invalid_argument("env.depth_width: the depth image is navigate's (task is \"" +
                                task + "\")");
  }
  if (task != "navigate" && target.z() - start_radius < 0.1) {
    throw std::invalid_argument(
        "env.target's height must exceed start_radius by 0.1 m: a start "
        "would be in the floor");
  }
}

QuadParams EnvParams::Vehicle() const { return *BuiltinVehicle(vehicle); }

bool EnvParams::Varies() const {
  return vary_mass > 0 || vary_inertia > 0 || vary_thrust > 0 || vary_yaw_moment > 0 ||
         vary_motor_lag > 0 || vary_rotor_limit > 0;
}

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
  for (std::string& name : FindEnvTask(task).extra_names(*this)) names.push_back(std::move(name));
  return names;
}

const std::vector<std::string>& EnvParams::RewardTermNames() const {
  return FindEnvTask(task).term_names;
}

}  // namespace aerobox
