// Several vehicles in one world: each flies its own flight (FlightRun: its controller, rate,
// take-off, rules and observers) in one MuJoCo world that steps once for all of them; a contact
// between two vehicles ends both flights as a collision naming the other; a vehicle above
// another pushes it down (the downwash model, optional); and space-time reservations keep
// the plans of several vehicles apart (prioritised planning).
#pragma once

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "common/schema.h"
#include "mission/flight.h"
#include "sim/simulation.h"

namespace aerobox {

// What a scenario's [swarm] table sets.
struct SwarmParams {
  // "prioritised": in the order given, each vehicle's trajectory waits at its start (or takes a
  // detour) until it keeps clear of the trajectories of those before it; "none": every vehicle
  // flies its own plan as if alone.
  std::string planning = "prioritised";
  double separation = 0.1;  // [m] kept between two vehicles, beyond both their radii
  double wait_step = 0.1;   // [s] a start is delayed in steps of this ...
  double max_wait = 30.0;   // [s] ... up to this, before a detour is tried
  // [s] a vehicle that starts on the floor climbs to its trajectory's start for this long before
  // the trajectory starts (its clock is the shared one: FlightLoop::shared_clock)
  double takeoff_time = 1.5;
  // The downwash of a vehicle above another (gym-pybullet-drones' model, BaseAviary._downwash,
  // from SiQi Zhou's measurements of Crazyflies at the Dynamic Systems Lab): on the lower, a
  // force -a exp(-(d_xy / b)^2 / 2) along z with a = c1 (r / (4 dz))^2 and b = c2 dz + c3, for
  // an upper vehicle dz above and d_xy across (within 10 m) whose propellers have radius r.
  bool downwash = false;
  double downwash_c1 = 2267.18;  // [N] the model's coefficients, fitted to the Crazyflie 2.x
  double downwash_c2 = 0.16;     // [-]
  double downwash_c3 = -0.11;    // [m]

  void Describe(Archive& a);  // [swarm] (common/schema.h)
  // Throws std::invalid_argument naming the field.
  void Validate() const;
};

// The downwash force [N] of a vehicle at `upper` [m] on one at `lower` [m], the upper's
// propellers of radius `propeller_radius` [m] (SwarmParams::downwash): (0, 0, -f) along the
// lower vehicle's body axes (FlySwarm turns it into the world); zero when `upper` is not above
// `lower` or is 10 m or more away across. Unlike the original, |b| is kept above 1 mm (b
// crosses 0 at dz = 0.69 m, where the original divides by zero).
Vec3 DownwashForce(const Vec3& upper, const Vec3& lower, double propeller_radius,
                   const SwarmParams& params);

// A vehicle's radius for separation [m]: half its collision box's diagonal.
double VehicleRadius(const QuadParams& vehicle);

// One vehicle of a flight of several.
struct SwarmVehicle {
  std::string name;  // as its elements are named in the scene (Simulation's vehicle names)
  Reference reference;
  FlightLoop loop;  // its vehicle, controller, rate, inner loops, air, sensors, telemetry
  std::optional<FlightParams> flight;  // its own flight settings; empty: FlySwarm's
};

struct SwarmFlightResult {
  std::vector<FlightResult> flights;  // one per vehicle, in the order given
  // the least distance between two vehicles' centres over the flight [m], when, and which
  double min_separation = std::numeric_limits<double>::infinity();
  double min_separation_time = 0.0;            // [s]
  std::string closest_pair;                    // "cf1 and cf2"
  std::vector<double> vehicle_min_separation;  // [m] each vehicle's least distance to another
  // [m] each vehicle's least clearance to another: the distance between centres less both
  // radii (VehicleRadius), as the clearance to the map is a gap (< 0: their spheres overlap)
  std::vector<double> vehicle_min_clearance;
  double time = 0.0;  // [s] when the last flight ended
  bool AllReached() const;
};

// Flies every vehicle from where it is in `sim` (vehicle i is sim's vehicle i) until every
// flight has ended. A vehicle whose flight ended while it still flies (it arrived, timed out,
// missed a goal, or was stopped) holds its reference's end while the others fly, and a contact
// then is its collision; one that crashed or whose controller failed has its rotors cut.
// `after_step`, when given, is called after each step of the world with the flight's time [s].
// Throws std::invalid_argument for bad parameters (a vehicle count other than the world's).
SwarmFlightResult FlySwarm(const std::vector<SwarmVehicle>& vehicles, const FlightParams& params,
                           const SwarmParams& swarm, Simulation* sim,
                           const std::function<void(double t)>& after_step = {});

// A reservation in space and time: where a vehicle of `radius` [m] is at each time [s] of the
// shared clock (before its reference starts: at its start; after: at its end).
struct Reservation {
  Reference reference;
  double radius = 0.0;  // [m]
};

// The reference `reference` started `delay` [s] later: at rest at its start until then.
Reference Delayed(const Reference& reference, double delay);

// The least distance [m] between the centres of two reserved vehicles, less both radii and
// `separation`, over the time both references take (sampled every 10 ms), and when [s].
struct Conflict {
  double margin = std::numeric_limits<double>::infinity();  // [m] < 0: they come too close
  double time = 0.0;                                        // [s]
};
Conflict Check(const Reservation& a, const Reservation& b, double separation);

// The smallest delay [s] from `min_delay` on (in steps of wait_step, a multiple of 10 ms, up to
// max_wait) that keeps `candidate` clear of every reservation (checked every 10 ms); none when
// there is no such delay. Ctrl-C stops it (common/stop.h).
std::optional<double> ConflictFreeDelay(const Reservation& candidate,
                                        const std::vector<Reservation>& reserved,
                                        const SwarmParams& params, double min_delay = 0.0);

}  // namespace aerobox
