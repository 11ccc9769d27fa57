// The learning environments' parameters, through the schema (common/schema.h): the task, the
// vehicle, the action level and its scaling, the observation's attitude form, the episode, the
// random start, the reward's weights, and each task's own (track_*, navigate's map, forest and
// range sensor). Python's aerobox.envs takes them as keyword arguments.
#pragma once

#include <string>
#include <vector>

#include "common/schema.h"
#include "common/types.h"
#include "vehicle/quad_params.h"

namespace aerobox {

struct EnvParams {
  // "hover" (reach and hold `target`), "track" (follow a random circle or figure-8 around
  // `target`), "navigate" (reach a random goal through a map of boxes), or a registered task
  // (env_task.h).
  std::string task = "hover";
  std::string vehicle = "crazyflie";  // a built-in vehicle (vehicle/quad_params.h)
  // The physics: "mujoco" (MuJoCo 2.2, the reference), or "rigid" (the vehicle as a lone rigid
  // body integrated as MuJoCo integrates it, with exact box contacts: sim/rigid_body.h).
  std::string backend = "mujoco";
  // What the action commands, each component in [-1, 1] (docs/learning.md gives the scaling):
  // "thrusts" (four rotor thrusts), "ctbm" (collective thrust and body moments), "ctbr"
  // (collective thrust and body rates), "ctatt" (collective thrust and roll, pitch, yaw),
  // "velocity" (world velocity and yaw, through aerobox's velocity loop at the control rate).
  // aerobox's inner loops run below it at the physics rate.
  std::string action = "ctbr";
  // The attitude in the observation: "matrix" (R_WB, row by row) or "quaternion" (w, x, y, z,
  // with w >= 0).
  std::string attitude = "matrix";
  double control_rate = 100.0;    // [Hz] one step(); must divide physics_rate
  double physics_rate = 1000.0;   // [Hz] the physics' steps (the inner loops run at it)
  double episode_time = 10.0;     // [s] then truncated
  Vec3 target = Vec3(0, 0, 1.5);  // [m] world ENU
  double start_radius = 1.0;      // [m] the start is uniform in this ball around the target
  double start_speed = 0.5;       // [m/s] at most, in a random direction
  double start_tilt = 0.5;        // [rad] at most, about a random horizontal axis; yaw random
  double start_rate = 1.0;        // [rad/s] at most, in a random direction
  double bounds_radius = 3.0;     // [m] from the target: beyond, the episode terminates
  double max_rate = 10.0;         // [rad/s] of body rate at action +-1 ("ctbr")
  double max_tilt = 0.6;          // [rad] of roll and pitch at action +-1 ("ctatt")
  double max_speed = 2.0;         // [m/s] of each velocity component at action +-1 ("velocity")
  // track: the reference, drawn per episode: a circle or a figure-8 (Gerono's lemniscate) in a
  // horizontal plane through `target`, a random size up to track_size, heading and phase, at a
  // speed up to track_speed; the observation holds it now and track_points samples ahead.
  std::string track_shape = "both";  // "circle", "figure8" or "both" (either, at random)
  double track_size = 1.0;           // [m] the circle's radius, the figure-8's half-length
  double track_speed = 1.0;          // [m/s] the reference's fastest
  int track_points = 3;              // samples of the reference ahead
  double track_spacing = 0.1;        // [s] between them
  // navigate: the map (an aerobox map file; "" for a seeded random forest), the start and goal
  // drawn per episode in its free space, and the range sensor in the observation.
  std::string map;
  double forest_size = 10.0;    // [m] the forest's square side
  double forest_height = 4.0;   // [m]
  int forest_trees = 30;        // trunks: boxes 0.2 to 0.5 m square, the forest's height
  int forest_seed = 1;          // the forest's layout (the same for every episode and world)
  double goal_distance = 4.0;   // [m] between the start and the goal, at least
  double arrival_radius = 0.3;  // [m] from the goal: arrived, the episode ends
  int range_rays = 16;     // horizontal rays (world frame, from +x anticlockwise), then down, up
  double range_max = 4.0;  // [m] a ray's reach
  // navigate: a depth image in the observation, after the ranges (0 x 0: none): the camera of
  // [sensing] kind "depth" (87 x 58 deg, on the nose, looking along body x) reaching range_max;
  // per pixel, rows from the top, the depth along the optical axis [m], range_max where
  // nothing is within reach
  int depth_width = 0;   // [px]
  int depth_height = 0;  // [px]
  // the reward per step: alive - position |p - target| - velocity |v| - rate |w| - action |a|^2
  double reward_alive = 1.0;
  double reward_position = 1.0;  // [1/m]
  double reward_velocity = 0.1;  // [s/m]
  double reward_rate = 0.05;     // [s/rad]
  double reward_action = 0.01;
  double reward_progress = 10.0;  // [1/m] navigate: times the step's approach to the goal
  double reward_arrival = 10.0;   // navigate: once, on arriving
  // Domain randomisation, drawn per episode from its own seeded stream: each physical value
  // times a factor uniform in [1 - f, 1 + f] (per rotor for the rotors'), while the inner loops
  // keep the nominal vehicle; 0 varies nothing.
  double vary_mass = 0.0;
  double vary_inertia = 0.0;      // one factor for the three principal moments
  double vary_thrust = 0.0;       // thrust produced per newton commanded
  double vary_yaw_moment = 0.0;   // reaction moment per newton
  double vary_motor_lag = 0.0;    // the motor lag's time constant
  double vary_rotor_limit = 0.0;  // the largest thrust command
  double wind_speed = 0.0;        // [m/s] the mean wind at most, horizontal, any direction
  double wind_turbulence = 0.0;   // [m/s] Dryden's horizontal intensity at most (vertical: half)
  // [m/s] a gust's peak at most: one per episode, horizontal, any direction, starting at a
  // random time of the episode, 1 to 3 s long with 0.5 s rise and fall
  double gust_speed = 0.0;
  bool drag = false;  // body and rotor drag (on whenever there is wind)
  // The observation from aerobox's sensors and estimator (an IMU and motion capture at their
  // defaults, docs/scenario-keys.md's [sensors]) instead of the truth; the inner loops fly on
  // it too. vary_sensor_noise: their noise times a factor in [1 - f, 1 + f].
  bool sensors = false;
  double vary_sensor_noise = 0.0;

  void Describe(Archive& a);
  // Throws std::invalid_argument naming the field (ranges, a rate that does not divide the
  // physics, a known vehicle).
  void Validate() const;
  QuadParams Vehicle() const;  // the built-in vehicle `vehicle` names
  bool Varies() const;         // any of the vehicle's vary_* is set
  int ActionSize() const { return 4; }
  int AttitudeSize() const { return attitude == "matrix" ? 9 : 4; }
  // relative position (3), velocity (3), attitude, body rates (3), the last action, then the
  // task's own components
  int ObservationSize() const { return static_cast<int>(ObservationNames().size()); }
  // One name per observation component ("dx", "vx", "R11" or "qw", "wx", "a0", ..., then the
  // task's), in order.
  std::vector<std::string> ObservationNames() const;
  // The names of the reward's terms, in the order EnvWorld reports them (the task's).
  const std::vector<std::string>& RewardTermNames() const;
};

}  // namespace aerobox
