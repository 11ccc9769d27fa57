#include "envs/env_params.h"

#include <cmath>
#include <stdexcept>

#include "common/number_format.h"
#include "envs/env_task.h"

namespace aerobox {

namespace {

// The environment's keys: the task, the vehicle, the physics, the action and the episode's start.
void DescribeWorld(Archive& a, EnvParams* p) {
  a.Choice({"task", "",
            "hover: reach and hold the target; track: follow a random trajectory; "
            "navigate: reach a goal through a map of boxes"},
           &p->task, EnvTaskNames());
  a.Choice({"vehicle", "", "a built-in vehicle"}, &p->vehicle, {"crazyflie", "tello"});
  a.Choice({"backend", "",
            "the physics: MuJoCo, or the rigid body integrated as MuJoCo integrates it (faster; "
            "box contacts end the episode as on MuJoCo)"},
           &p->backend, {"mujoco", "rigid"});
  a.Choice({"action", "", "what the action commands, each component in [-1, 1]"}, &p->action,
           {"thrusts", "ctbm", "ctbr", "ctatt", "velocity"});
  a.Choice({"attitude", "", "the attitude in the observation: R_WB row by row, or w, x, y, z"},
           &p->attitude, {"matrix", "quaternion"});
  a.Number({"control_rate", "Hz", "steps per second; must divide physics_rate"}, &p->control_rate,
           1, 1000);
  a.Number({"physics_rate", "Hz", "physics steps per second (the inner loops run at it)"},
           &p->physics_rate, 50, 10000);
  a.Number({"episode_time", "s", "then the episode is truncated"}, &p->episode_time, 0.01, 3600);
  a.Vector({"target", "m", "the point to reach and hold (world ENU)"}, &p->target, -1e3, 1e3);
  a.Number({"start_radius", "m", "the start is uniform in this ball around the target"},
           &p->start_radius, 0, 100);
  a.Number({"start_speed", "m/s", "the start's speed at most, in a random direction"},
           &p->start_speed, 0, 20);
  a.Number({"start_tilt", "rad", "the start's tilt at most; its yaw is random"}, &p->start_tilt, 0,
           1.5);
  a.Number({"start_rate", "rad/s", "the start's body rate at most"}, &p->start_rate, 0, 20);
  a.Number({"bounds_radius", "m", "this far from the target, the episode terminates"},
           &p->bounds_radius, 0.1, 1e3);
  a.Number({"max_rate", "rad/s", "body rate at action +-1 (ctbr)"}, &p->max_rate, 0.1, 50);
  a.Number({"max_tilt", "rad", "roll and pitch at action +-1 (ctatt)"}, &p->max_tilt, 0.05, 1.5);
  a.Number({"max_speed", "m/s", "each velocity component at action +-1 (velocity)"}, &p->max_speed,
           0.1, 20);
}

// The environment's keys: track's reference.
void DescribeTrack(Archive& a, EnvParams* p) {
  a.Choice({"track_shape", "", "track: the reference's shape, drawn per episode"}, &p->track_shape,
           {"both", "circle", "figure8"});
  a.Number({"track_size", "m", "track: the circle's radius, the figure-8's half-length, at most"},
           &p->track_size, 0.1, 100);
  a.Number({"track_speed", "m/s", "track: the reference's top speed, at most"}, &p->track_speed,
           0.05, 20);
  a.Integer({"track_points", "", "track: reference samples ahead in the observation"},
            &p->track_points, 0, 50);
  a.Number({"track_spacing", "s", "track: time between the samples ahead"}, &p->track_spacing,
           0.001, 10);
}

// The environment's keys: navigate's map, forest and sensing.
void DescribeNavigate(Archive& a, EnvParams* p) {
  a.Text({"map", "", "navigate: an aerobox map file (\"\": a random forest)"}, &p->map);
  a.Number({"forest_size", "m", "navigate: the random forest's square side"}, &p->forest_size, 2,
           1000);
  a.Number({"forest_height", "m", "navigate: the random forest's height"}, &p->forest_height, 1,
           100);
  a.Integer({"forest_trees", "", "navigate: the random forest's trunks"}, &p->forest_trees, 0,
            10000);
  a.Integer({"forest_seed", "", "navigate: the random forest's layout"}, &p->forest_seed, 0,
            1000000000);
  a.Number({"goal_distance", "m", "navigate: between the start and the goal, at least"},
           &p->goal_distance, 0, 1e3);
  a.Number({"arrival_radius", "m", "navigate: this near the goal, arrived"}, &p->arrival_radius,
           0.01, 100);
  a.Integer({"range_rays", "", "navigate: horizontal range rays (then one down, one up)"},
            &p->range_rays, 0, 360);
  a.Number({"range_max", "m", "navigate: a range ray's reach"}, &p->range_max, 0.1, 100);
  a.Integer({"depth_width", "px", "navigate: a depth image in the observation, its columns"},
            &p->depth_width, 0, 256);
  a.Integer({"depth_height", "px", "navigate: the depth image's rows"}, &p->depth_height, 0, 256);
}

// The environment's keys: the reward's weights.
void DescribeReward(Archive& a, EnvParams* p) {
  a.Number({"reward_alive", "", "added every step"}, &p->reward_alive, 0, 1e3);
  a.Number({"reward_position", "1/m", "times the distance to the target, taken off"},
           &p->reward_position, 0, 1e3);
  a.Number({"reward_velocity", "s/m", "times the speed, taken off"}, &p->reward_velocity, 0, 1e3);
  a.Number({"reward_rate", "s/rad", "times the body rate's norm, taken off"}, &p->reward_rate, 0,
           1e3);
  a.Number({"reward_action", "", "times the action's squared norm, taken off"}, &p->reward_action,
           0, 1e3);
  a.Number({"reward_progress", "1/m", "navigate: times the step's approach to the goal"},
           &p->reward_progress, 0, 1e3);
  a.Number({"reward_arrival", "", "navigate: once, on arriving"}, &p->reward_arrival, 0, 1e6);
}

// The environment's keys: domain randomisation, wind and sensors.
void DescribeRandomisation(Archive& a, EnvParams* p) {
  // per episode, each a factor in [1 - f, 1 + f] (per rotor for the rotors')
  a.Number({"vary_mass", "", "per episode: the mass times 1 +- up to this"}, &p->vary_mass, 0, 0.5);
  a.Number({"vary_inertia", "", "per episode: the moments of inertia times 1 +- up to this"},
           &p->vary_inertia, 0, 0.5);
  a.Number({"vary_thrust", "", "per episode: each rotor's thrust per newton commanded, 1 +-"},
           &p->vary_thrust, 0, 0.5);
  a.Number({"vary_yaw_moment", "", "per episode: each rotor's reaction moment, 1 +-"},
           &p->vary_yaw_moment, 0, 0.5);
  a.Number({"vary_motor_lag", "", "per episode: each rotor's motor lag, 1 +-"}, &p->vary_motor_lag,
           0, 0.9);
  a.Number({"vary_rotor_limit", "", "per episode: each rotor's largest thrust command, 1 +-"},
           &p->vary_rotor_limit, 0, 0.5);
  a.Number({"wind_speed", "m/s", "per episode: a horizontal mean wind up to this, any direction"},
           &p->wind_speed, 0, 20);
  a.Number({"wind_turbulence", "m/s", "per episode: Dryden turbulence up to this intensity"},
           &p->wind_turbulence, 0, 10);
  a.Number({"gust_speed", "m/s", "per episode: one gust of a peak up to this, at a random time"},
           &p->gust_speed, 0, 20);
  a.Boolean({"drag", "", "body and rotor drag (on whenever there is wind)"}, &p->drag);
  a.Boolean({"sensors", "", "observe through aerobox's IMU, motion capture and estimator"},
            &p->sensors);
  a.Number({"vary_sensor_noise", "", "per episode: the sensors' noise times 1 +- up to this"},
           &p->vary_sensor_noise, 0, 0.9);
}

}  // namespace

void EnvParams::Describe(Archive& a) {
  DescribeWorld(a, this);
  DescribeTrack(a, this);
  DescribeNavigate(a, this);
  DescribeReward(a, this);
  DescribeRandomisation(a, this);
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
