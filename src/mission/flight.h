// The closed loop: a plain function composing the simulation, a controller with aerobox's inner
// loops below its command, and a reference, stepping at the physics rate and returning how the
// flight ended (after RotorPy's simulate()).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/flat_output.h"
#include "common/schema.h"
#include "control/controllers.h"
#include "disturbance/aero.h"
#include "disturbance/wind.h"
#include "estimation/sensing.h"
#include "map/map.h"
#include "sim/simulation.h"
#include "trajectory/polynomial.h"

namespace aerobox {

// What a scenario's [flight] table sets.
struct FlightParams {
  double settle_time = 5.0;       // [s] after the trajectory's end to reach the goal (DESIGN.md)
  double goal_tolerance = 0.10;   // [m] "reached": this close to the goal ...
  double goal_speed = 0.10;       // [m/s] ... and this slow
  double flyaway_distance = 2.0;  // [m] from the setpoint: the flight is lost
  bool face_travel = false;       // yaw along the travel; otherwise hold the start's
  // With face_travel: the yaw turns toward the reference this far ahead [m] (a camera along
  // body x then sees a turn before the vehicle takes it), at most this fast [rad/s] (a yaw that
  // follows the velocity of a slow, tight turn would spin the vehicle and saturate its rotors).
  double look_ahead = 1.0;               // [m]
  double yaw_rate = 2.0943951023931953;  // [rad/s] 120 deg/s
  // With face_travel: where the reference moves slower than FlightParams::kWaitSpeed (a start
  // from rest, a sharp turn), its clock stands while the yaw is further than this from the way
  // ahead [rad]: the camera sees where the vehicle goes before it goes (pi: never waits).
  double turn_first = 0.3490658503988659;     // [rad] 20 deg
  static constexpr double kWaitSpeed = 0.25;  // [m/s]

  void Describe(Archive& a);  // [flight] (common/schema.h)
  // Throws std::invalid_argument naming the field.
  void Validate() const;
};

enum class FlightStatus {
  kReachedGoal,
  kCollision,
  kTimeout,
  kNonFinite,
  kFlyAway,
  kSimulationWarning,  // MuJoCo warned (an engine reset, a full contact buffer): not trusted
  kMissedGoal,         // at the last goal, but a goal before it was never reached
  kControllerFailed,   // the controller gave no command (ControlStatus::kFailed): its message
  kTerminated,         // the loop's own rule ended it (FlightLoop::terminate)
};
const char* ToString(FlightStatus status);

// How many cells of an occupancy map built in flight are known.
struct OccupancySize {
  long occupied = 0;
  long free = 0;
};

// One row of telemetry per control step (each Controller::Update).
struct TelemetrySample {
  double t = 0.0;
  State state;
  FlatOutput setpoint;
  ControlCommand command;             // what the controller asked for
  InnerOutput inner;                  // what the inner loops made of it, down to the rotors
  Vec4 rotor_thrusts = Vec4::Zero();  // produced (after the motor lag) [N]
  double position_error = 0.0;        // |p - p_des| [m]
  double clearance = 0.0;             // to the nearest obstacle [m]
  std::vector<double> report;         // the controller's own columns (ReportColumns)
  int goal_index = 0;                 // a mission's goals reached so far (the next one's index)
  int replans = 0;                    // references replaced so far (FlightLoop::update_reference)
  OccupancySize map;                  // the occupancy map's cells (FlightLoop::map_size)
  Vec3 wind_W = Vec3::Zero();         // the wind at the vehicle [m/s]
  Vec3 aero_force_W = Vec3::Zero();   // drag on the vehicle [N]
  // With sensors on: the estimate the controller flew on, its error and the readings; empty
  // otherwise (the controller saw the true state).
  std::optional<EstimateSample> estimate;
};

struct FlightResult {
  FlightStatus status = FlightStatus::kTimeout;
  double time = 0.0;                 // [s] when the flight ended
  Vec3 end_position = Vec3::Zero();  // [m] where the vehicle was then
  // [s] of lifting from the floor to the trajectory's start before its clock started (0: the
  // flight began at the start); the tracking errors count from then
  double takeoff_time = 0.0;
  std::string obstacle;        // the geom hit, for kCollision
  std::string message;         // MuJoCo's warning, or the controller's failure
  std::string detail;          // kControllerFailed: the controller's detail (a traceback)
  double rms_error = 0.0;      // [m] tracking error from the trajectory's start
  double max_error = 0.0;      // [m]
  double min_clearance = 0.0;  // [m]
  long steps = 0;
  double control_rate = 0.0;  // [Hz] of the controller (and of the telemetry)
  double distance = 0.0;      // [m] flown
  double top_speed = 0.0;     // [m/s]
  // the largest rotor command as a fraction of the rotor's limit, and how long any rotor was
  // commanded at a limit (the mixer had no authority left there) [s]
  double peak_rotor_fraction = 0.0;
  double saturated_time = 0.0;
  // with sensors on: the estimate's position error |p_est - p| [m] over the flight
  double estimate_rms_error = 0.0;
  double estimate_max_error = 0.0;
  double max_wind = 0.0;  // [m/s] the strongest wind met
  // a mission's goals before the last: when each was reached [s], in order (as many as were)
  std::vector<double> goal_times;
  int replans = 0;  // how often the reference was replaced in flight
  double AverageSpeed() const { return time > 0 ? distance / time : 0.0; }  // [m/s]
};

// What the vehicle follows: position and its derivatives (up to snap) at time t [s] from the
// start, for t in [0, duration]; beyond, the end point is held.
struct Reference {
  double duration = 0.0;
  std::function<Vec3(double t, int derivative)> evaluate;
  // yaw [rad] and yaw rate [rad/s] at t, when the reference has its own heading; empty: the
  // start's yaw is held, or the yaw follows the travel (FlightParams::face_travel)
  std::function<std::pair<double, double>(double t)> heading;
};
Reference ReferenceOf(const PiecewiseTrajectory& trajectory);

// The scene puts the vehicle at rest at the requested start (on the floor when the start is at
// floor level). A start in the air becomes the trajectory's first point `used`, hovering.
void PlaceVehicleAtStart(const Map& map, const QuadParams& vehicle, const Vec3& requested,
                         const Vec3& used, VehiclePhysics* sim);

// When a flight is complete (FlightStatus::kReachedGoal): the vehicle rests at a point within
// a tolerance, below a speed (the goal's, FlightParams, at the reference's end).
struct Completion {
  enum class Kind {
    kAtEnd,    // at the reference's end, once the reference's time has run out
    kAtPoint,  // at `point`, from the reference's time `from` [s] on, whatever its duration (a
               // trajectory known only by its end: flightsim's and RotorPy's rule)
    kNever,    // never: the flight ends at its time limit or on a failure
  };
  Kind kind = Kind::kAtEnd;
  Vec3 point = Vec3::Zero();  // [m]
  double from = 0.0;          // [s]
  // kAtPoint's own tolerances (with no end time, the goal's would end an approach early):
  // flightsim's and RotorPy's, 2 cm and 3 cm/s
  double point_tolerance = 0.02;  // [m]
  double point_speed = 0.03;      // [m/s]
};

// The parts of a flight besides the simulation and the reference.
struct FlightLoop {
  const QuadParams* vehicle = nullptr;
  Controller* controller = nullptr;
  double control_rate = 250.0;  // [Hz]: must divide the physics rate
  InnerLoopParams inner;
  // distance from the vehicle at a point to the nearest obstacle [m]; may be empty
  std::function<double(const Vec3&)> clearance;
  // one sample per control step; may be empty
  std::function<void(const TelemetrySample&)> telemetry;
  // The air and the sensors; all off by default, and then the flight is the ideal one, step
  // for step. With sensors on, the controller and the inner loops fly on the estimate.
  WindParams wind;
  // The wind [m/s] at a point p_W [m] at flight time t [s], asked before each physics step: a
  // user's own wind (RotorPy's wind profiles' update(t, position)), in place of `wind`. It acts
  // through the drag (`aero`). Empty: `wind` blows.
  std::function<Vec3(double t, const Vec3& p_W)> wind_source;
  AeroParams aero;
  SensorParams sensors;
  std::uint64_t seed = 1;  // the turbulence's and the sensors' (common/seed.h streams)
  // A mission's goals before the reference's end, in order: each is reached within the goal
  // tolerance (and below the goal speed when the mission stops at its goals); the flight
  // succeeds only when all were, in order.
  std::vector<Vec3> goals;
  bool stop_at_goals = false;
  // Called at each control step (once airborne) with the flight time, the reference's time
  // [s], the state the controller sees, the goals reached and the reference flown; a reference
  // it returns is flown from then on, on the same clock (it must agree with the current one up
  // to now, so the setpoint does not jump). Empty: the reference is flown as given.
  std::function<std::optional<Reference>(double t, double tr, const State& state, int goals_reached,
                                         const Reference& current)>
      update_reference;
  // The occupancy map's size now, for telemetry (a depth camera's map); empty: none.
  std::function<OccupancySize()> map_size;
  double ground_z = 0.0;  // [m] the floor's height, for the turbulence's scale lengths
  Completion completion;
  // Asked at each control step with the flight time [s] and the true state: true ends the flight
  // (FlightStatus::kTerminated). Empty: no rule of its own.
  std::function<bool(double t, const State& state)> terminate;
  // The reference's clock is the flight's: neither a take-off from the floor nor a turn toward
  // the way ahead (FlightParams::turn_first) holds it, so that several vehicles keep the timing
  // their plans were kept apart with (the reference must give the climb time itself).
  bool shared_clock = false;
  // [s] of flight from which the setpoint is NaN (a fault test's; infinity: never)
  double nonfinite_setpoint_from = std::numeric_limits<double>::infinity();
};

class VehicleWorld;  // mission/flight_parts.h

// Flies the reference from the simulation's current state (at rest on the floor or in the air
// at the trajectory's start) and holds its end until reached. A vehicle resting on the floor
// may touch it until it lifts off; any other contact is a collision. Throws
// std::invalid_argument for bad parameters (a rate that does not divide the physics rate).
FlightResult FlyTrajectory(const Reference& reference, const FlightParams& params,
                           const FlightLoop& loop, Simulation* sim);

// The same in a world already made (its air, sensors and estimator going on from where they
// are); the loop's own wind, drag, sensors, seed and inner-loop parameters are the world's, not
// read again. The flight's clock starts at the world's time now. The take-off, the rules that
// end the flight and the observers are the standard ones (StandardParts); to fly other parts,
// see FlyTrajectory(..., FlightParts) in mission/flight_parts.h.
FlightResult FlyTrajectory(const Reference& reference, const FlightParams& params,
                           const FlightLoop& loop, VehicleWorld* world);

// The same with the controller `control.kind` names, made for `vehicle`.
FlightResult FlyTrajectory(const Reference& reference, const FlightParams& params,
                           const QuadParams& vehicle, const ControllerConfig& control,
                           const std::function<double(const Vec3&)>& clearance,
                           const std::function<void(const TelemetrySample&)>& telemetry,
                           Simulation* sim);

}  // namespace aerobox
