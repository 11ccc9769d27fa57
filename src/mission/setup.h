// What a flight needs to know about its world: the map, where it starts and ends (and where
// those came from, for messages), the seed and the planning settings.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "control/controllers.h"
#include "geometry/collision_world.h"
#include "map/map.h"
#include "map/map_reader.h"
#include "mission/flight.h"
#include "mission/planning_settings.h"
#include "mission/replanning.h"
#include "mission/swarm.h"
#include "vehicle/quad_params.h"

namespace aerobox {

// FlightSetup::start_origin when neither the user nor the map gave a start and no free spot
// was found for one: a scene can still be made; planning refuses.
inline constexpr const char* kNoStart = "none";

// One vehicle of several in one world (a scenario's [[vehicles]]): its own name, vehicle,
// controller, start and goal; the map, the air, the planning and flight settings are shared.
struct SwarmMember {
  std::string name;                    // unique; its folder of outputs, its elements' prefix
  std::string vehicle_kind = "tello";  // the built-in its vehicle is
  QuadParams vehicle;
  ControllerConfig controller;
  Vec3 start = Vec3::Zero();  // [m]
  Vec3 goal = Vec3::Zero();   // [m]
  std::vector<Vec3> via;      // [m] a mission's goals before `goal`, in order
  SourceLocation where;       // its table, for messages
};

// A map ready to fly with everything a scenario sets: where start and goal came from is kept
// for messages and summaries. One QuadParams feeds the scene, the collision worlds and the
// controller.
struct FlightSetup {
  std::string name;
  Map map;
  MapFormat map_format = MapFormat::kTxt;
  Vec3 start = Vec3::Zero();
  std::string start_origin;  // "command line", "scenario", "map file", "start/goal file", "default"
  SourceLocation start_where;  // the file and line that gave it, for messages
  std::optional<Vec3> goal;
  std::string goal_origin;
  SourceLocation goal_where;
  // A mission: the goals before `goal`, in order (empty: one goal). With stop_at_goals the
  // vehicle stops at each for `hold` seconds; otherwise one trajectory flies through them.
  std::vector<Vec3> via;
  bool stop_at_goals = false;
  double hold = 0.0;  // [s]
  // Boxes of `map` the planner does not know before take-off (one flag per box; empty: none),
  // the sensor that reveals them and how the flight replans around them.
  std::vector<bool> unknown;
  SensingParams sensing;
  ReplanParams replan;
  bool HasUnknown() const;
  // What the controller's acceleration and rotor thrusts come from when it measures them (indi,
  // or the observer): "imu" with sensors on, else "ground truth (no IMU: sensors off)"; ""
  // for a controller that does not.
  std::string ControllerMeasures() const;
  std::uint64_t seed = 1;
  PlanningSettings planning;
  std::string vehicle_kind = "tello";  // the built-in the vehicle started from ([vehicle] kind)
  QuadParams vehicle;                  // with the scenario's overrides
  ControllerConfig controller;         // [controller]
  FlightParams flight;                 // [flight]
  WindParams wind;                     // [wind]
  AeroParams aero;                     // [aero]
  SensorParams sensors;                // [sensors]
  // Several vehicles in one world ([[vehicles]]; empty: the set-up's own vehicle alone) and how
  // they keep apart ([swarm]).
  std::vector<SwarmMember> vehicles;
  SwarmParams swarm;
  // The set-up of `vehicles[i]` as if it flew alone: its vehicle, controller, start and goal.
  FlightSetup Member(size_t i) const;
  // Faults the fault tests inject: the command reads them (AEROBOX_FAULT,
  // common/fault_injection.h); the domain only obeys them.
  struct Faults {
    double nonfinite_setpoint_from = std::numeric_limits<double>::infinity();  // [s] of flight
    bool ipopt_failure = false;  // every Ipopt solve reports a failure
  } faults;

  // The vehicle's box grown by the planner's clearance, and by the trajectory's.
  CollisionParams PlannerCollision() const;
  CollisionParams TrajectoryCollision() const;
  // Everything a scenario set, checked; throws std::invalid_argument naming the field.
  void Validate() const;
};

// se3's position integral in wind (Se3Params::position_integral), when [controller] gives none:
// measured on the robustness maps at 4 m/s mean wind with Dryden turbulence, 39 of 40 flights
// reached the goal with it, none without; in still air it would cost tracking (the window's
// RMS 0.53 -> 0.62 cm), so still air flies without it.
inline const Vec3 kSe3WindIntegral = Vec3(12.0, 12.0, 12.0);  // [1/s^3]

// The controllers' defaults that follow the air, unless [controller] gave them (`*_given`): a
// controller in drag feeds its drag forward; se3 in wind, without the disturbance observer,
// integrates its position error (kSe3WindIntegral). For the set-up's controller and each of
// its vehicles'.
void FollowTheAir(bool feedforward_given, bool integral_given, FlightSetup* setup);

// Gives a flight loop the set-up's air and sensors: wind, drag, sensors, seed and floor.
void AddAirAndSensors(const FlightSetup& setup, FlightLoop* loop);

// The MJCF scene of a set-up: the vehicle rests at the start, the chase camera faces the goal;
// several vehicles ([[vehicles]]) each rest at their own start in their own colour.
// `keep_boxes`: see SceneOptions (empty: every box of the map).
std::string SceneMjcfFor(const FlightSetup& setup, const std::vector<bool>& keep_boxes = {});

}  // namespace aerobox
