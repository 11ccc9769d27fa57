// Scenarios (scenes/<name>/scenario.toml) and the loading every command shares: a scenario or a
// bare map file becomes a map with a start and a goal.
#pragma once

#include <cstdint>
#include <istream>
#include <optional>
#include <string>
#include <vector>

#include "common/error.h"
#include "map/map.h"
#include "map/map_reader.h"
#include "mission/setup.h"

namespace aerobox {

// scenario.toml:
//   name = "window"                      # optional; default: the scenario file's folder name
//   map = "map.json"                     # required; relative to the scenario file
//   start = [0.7, -4.3, 0.7]             # optional when the map gives one [m]
//   goal = [8.0, 18.0, 3.0]              # optional when the map gives one [m]
//   goals = [[..], [..], [..]]           # or a mission through several, in order [m]
//   stop_at_goals = false                # stop at each goal (else fly through)
//   hold = 0.0                           # [s] at each intermediate goal, when stopping
//   seed = 1                             # optional; seeds every random generator
//   [planner]                            # optional: clearance, max_iterations, time_budget,
//                                        #   max_step, goal_bias, rewire_factor, informed,
//                                        #   shortcut_attempts (see planning_settings.h)
//   [trajectory]                         # optional: max_speed, max_accel, clearance,
//                                        #   corridors, corridor_growth, samples_per_segment,
//                                        #   max_refinements
//   [vehicle]                            # optional: kind ("tello", "crazyflie") and
//                                        #   overrides of its values (README: The vehicle)
//   [controller]                         # optional: kind ("cascade", "se3", "indi"), rate, gains
//   [flight]                             # optional: settle_time, tolerances, yaw
//   [wind]                               # optional: mean, turbulence, intensity, gusts
//   [aero]                               # optional: drag, body_drag, rotor_drag
//   [sensors]                            # optional: imu, position, estimator
//   unknown = [3, 7] | unknown_fraction = 0.3 | unknown_map = "more.txt"
//   [sensing] [replan]                   # optional: the range sensor, replanning
//   [render]                             # optional table (no keys defined yet)
//   [[vehicles]]                         # several vehicles in one world: name, start, goal,
//                                        #   kind, controller, rate (VehicleEntry)
//   [swarm]                              # how they keep apart: planning, separation, downwash

// One [[vehicles]] table: a vehicle of several in one world. Its kind and controller default to
// the scenario's [vehicle] and [controller]; a [vehicles.vehicle] table after it changes its
// vehicle's values as [vehicle] does; goals = [[x, y, z], ...] in place of goal flies a mission.
struct VehicleEntry {
  std::string name;
  std::string kind;        // "": the scenario's [vehicle] (with its overrides)
  std::string controller;  // "": the scenario's [controller] kind
  double rate = 0.0;       // [Hz] 0: the scenario's [controller] rate
  Vec3 start = Vec3::Zero();
  Vec3 goal = Vec3::Zero();
  std::vector<Vec3> via;  // goals = [...]: the goals before the last (which is `goal`)
  int line = 0;           // where its table starts
  void Describe(Archive& a);
};

struct Scenario {
  std::string name;
  std::string file;      // the scenario file, for messages
  std::string map_path;  // resolved against the scenario file's folder
  int map_line = 0;      // where the keys were given, for messages
  std::optional<Vec3> start;
  int start_line = 0;
  std::optional<Vec3> goal;
  int goal_line = 0;
  // goals = [[x, y, z], ...]: a mission through each in order (the last is `goal`, the others
  // go into `via`); stop_at_goals: stop at each (for `hold` seconds) instead of flying through
  std::vector<Vec3> via;
  bool stop_at_goals = false;
  double hold = 0.0;  // [s]
  // boxes unknown to the planner: map box indices, a seeded share of the map's boxes, or the
  // boxes of another map file (added to the scene); [sensing] and [replan]
  std::vector<int> unknown;
  double unknown_fraction = 0.0;
  std::string unknown_map;  // resolved against the scenario's folder
  int unknown_line = 0;
  SensingParams sensing;
  ReplanParams replan;
  std::uint64_t seed = 1;
  PlanningSettings planning;
  std::string vehicle_kind = "tello";   // [vehicle] kind
  QuadParams vehicle;                   // the kind's values with the table's overrides
  ControllerConfig controller;          // [controller]
  bool drag_feedforward_given = false;  // [controller] drag_feedforward (else it follows [aero])
  bool se3_integral_given = false;  // [controller] se3_position_integral (else it follows [wind])
  bool yaw_given = false;   // [flight] yaw (else a depth camera turns the yaw along the travel)
  FlightParams flight;      // [flight]
  WindParams wind;          // [wind]
  AeroParams aero;          // [aero]
  bool aero_given = false;  // [aero] was there (else wind brings drag)
  SensorParams sensors;     // [sensors]
  std::vector<VehicleEntry> vehicle_entries;  // [[vehicles]] as given
  std::vector<SwarmMember> vehicles;  // ... each with its vehicle and controller (then read)
  SwarmParams swarm;                  // [swarm]
};

// A trajectory in the form aerobox's trajectory.csv has (header t,x,y,z,vx,vy,vz,ax,ay,az, one
// sample per row [s, m, m/s, m/s^2]); throws InputError naming the file and line.
std::vector<TrajectorySample> ReadTrajectoryCsv(std::istream& in, const std::string& file);

// Parses scenario text; throws InputError naming the file, line and key at fault.
Scenario ReadScenario(std::istream& in, const std::string& file);

// The reference of every scenario key the schema describes (common/schema.h), as Markdown: per
// table, each key's unit, default, valid range and meaning (`aerobox keys`; it is
// docs/scenario-keys.md).
std::string ScenarioKeyReference();

// One scenario key set from outside the file (`--set KEY=VALUE`, a sweep's grid): a dotted key
// and a TOML value; a bare word that is not TOML is taken as a string.
struct Setting {
  std::string key;       // "trajectory.max_speed", "controller.kind", "goal"
  std::string value;     // 2.0, "cascade", cascade, [9.0, 7.0, 1.5]
  SourceLocation where;  // where it was given, for messages
  std::string option;    // the command-line flag it stands for ("--max-speed"), named in messages
};

struct SetupOverrides {
  std::optional<Vec3> start;
  std::optional<Vec3> goal;
  std::vector<Vec3> via;  // --goal given several times: all but the last, in order
  std::optional<std::uint64_t> seed;
  // applied to the scenario's keys (or to a bare map's, as a scenario naming only the map)
  // before it is read; a setting the scenario's reader refuses is reported where the setting
  // was given
  std::vector<Setting> settings;
};

// "KEY=VALUE" from the command line; throws InputError naming `option`.
Setting ParseSetting(const std::string& text, const std::string& option);

// `path` is a scenario (.toml) or a map (.txt, .json, .csv). Start and goal come from, in order:
// the overrides, the scenario, the map file, a "<map stem>.startgoal.txt" file beside a map
// (RBE595's start and goal files). Without any start, the vehicle rests on the floor at the
// map's DefaultStart(). Throws InputError for any bad file.
FlightSetup LoadFlightSetup(const std::string& path, const SetupOverrides& overrides);
// The same from scenario text, read as if it were the file `file` (its name is the one messages
// give; a relative map path resolves against its folder).
FlightSetup LoadFlightSetupFromText(const std::string& text, const std::string& file,
                                    const SetupOverrides& overrides);

}  // namespace aerobox
