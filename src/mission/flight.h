// The closed loop: a plain function composing the simulation, the cascade and a trajectory,
// stepping at the physics rate, returning how the flight ended (after RotorPy's simulate()).
#pragma once

#include <functional>
#include <string>

#include "control/cascade.h"
#include "map/map.h"
#include "sim/simulation.h"
#include "trajectory/polynomial.h"

namespace aerobox {

struct FlightParams {
  CascadeParams cascade;
  double settle_time = 5.0;       // [s] after the trajectory's end to reach the goal (DESIGN.md)
  double goal_tolerance = 0.10;   // [m] "reached": this close to the goal ...
  double goal_speed = 0.10;       // [m/s] ... and this slow
  double flyaway_distance = 2.0;  // [m] from the setpoint: the flight is lost
  bool face_travel = false;       // yaw along the horizontal velocity; otherwise hold the start's

  void Validate() const;
};

enum class FlightStatus { kReachedGoal, kCollision, kTimeout, kNonFinite, kFlyAway };
const char* ToString(FlightStatus status);

// One row of telemetry per control (outer-loop) step.
struct TelemetrySample {
  double t = 0.0;
  State state;
  PositionSetpoint setpoint;
  CascadeOutput control;
  Vec4 rotor_thrusts = Vec4::Zero();  // produced (after the motor lag) [N]
  double position_error = 0.0;        // |p - p_des| [m]
  double clearance = 0.0;             // to the nearest obstacle [m]
};

struct FlightResult {
  FlightStatus status = FlightStatus::kTimeout;
  double time = 0.0;           // [s] when the flight ended
  std::string obstacle;        // the geom hit, for kCollision
  double rms_error = 0.0;      // [m] tracking error over the flight
  double max_error = 0.0;      // [m]
  double min_clearance = 0.0;  // [m]
  long steps = 0;
};

// What the vehicle follows: position and its derivatives at time t [s] from the start, for
// t in [0, duration]; beyond, the end point is held.
struct Reference {
  double duration = 0.0;
  std::function<Vec3(double t, int derivative)> evaluate;
};
Reference ReferenceOf(const PiecewiseTrajectory& trajectory);

// The scene puts the vehicle at rest at the requested start (on the floor when the start is at
// floor level). A start in the air becomes the trajectory's first point `used`, hovering.
void PlaceVehicleAtStart(const Map& map, const Vec3& requested, const Vec3& used, Simulation* sim);

// Flies the reference from the simulation's current state (at rest on the floor or in the air
// at the trajectory's start) and holds its end until reached. `clearance` gives the distance
// from the vehicle at a point to the nearest obstacle; `telemetry` gets one sample per control
// step (either may be empty). A vehicle resting on the floor may touch it until it lifts off;
// any other contact is a collision.
FlightResult FlyTrajectory(const Reference& reference, const FlightParams& params,
                           const QuadParams& vehicle,
                           const std::function<double(const Vec3&)>& clearance,
                           const std::function<void(const TelemetrySample&)>& telemetry,
                           Simulation* sim);

}  // namespace aerobox
