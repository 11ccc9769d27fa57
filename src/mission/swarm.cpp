#include "mission/swarm.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "mission/flight_parts.h"

namespace aerobox {

void SwarmParams::Describe(Archive& a) {
  a.Choice({"planning", "",
            "\"prioritised\": each vehicle in turn waits or detours until its trajectory keeps "
            "clear of those before it; \"none\": each flies its own plan"},
           &planning, {"prioritised", "none"});
  a.Number({"separation", "m", "kept between two vehicles, beyond both their radii"}, &separation,
           0, 10);
  a.Number({"wait_step", "s", "a start is delayed in steps of this ..."}, &wait_step, 0.01, 10);
  a.Number({"max_wait", "s", "... up to this, before a detour is tried"}, &max_wait, 0, 600);
  a.Boolean({"downwash", "", "a vehicle above another pushes it down (gym-pybullet-drones' model)"},
            &downwash);
  a.Number({"downwash_c1", "N", "the downwash model's first coefficient (Crazyflie 2.x fit)"},
           &downwash_c1, 0, 1e5);
  a.Number({"downwash_c2", "", "its second, the spread's growth with height"}, &downwash_c2, -10,
           10);
  a.Number({"downwash_c3", "m", "its third, the spread's offset"}, &downwash_c3, -10, 10);
}

void SwarmParams::Validate() const { ValidateFields(*this, "swarm"); }

Vec3 DownwashForce(const Vec3& upper, const Vec3& lower, double propeller_radius,
                   const SwarmParams& params) {
  constexpr double kReach = 10.0;        // [m] across: the model ignores vehicles farther
  constexpr double kLeastSpread = 1e-3;  // [m] |b| at least this (b crosses 0 at dz = 0.69 m)
  const double dz = upper.z() - lower.z();
  const double across = (upper - lower).head<2>().norm();
  if (!(dz > 0.0) || across >= kReach) return Vec3::Zero();
  const double a = params.downwash_c1 * std::pow(propeller_radius / (4.0 * dz), 2);
  const double b = std::max(std::abs(params.downwash_c2 * dz + params.downwash_c3), kLeastSpread);
  return Vec3(0.0, 0.0, -a * std::exp(-0.5 * std::pow(across / b, 2)));
}

double VehicleRadius(const QuadParams& vehicle) { return 0.5 * vehicle.collision_size.norm(); }

bool SwarmFlightResult::AllReached() const {
  return std::all_of(flights.begin(), flights.end(),
                     [](const FlightResult& f) { return f.status == FlightStatus::kReachedGoal; });
}

namespace {

// One vehicle's flight in the shared world: its world, its parts and its run.
struct Member {
  Member(const SwarmVehicle& v, const FlightParams& params, MujocoVehicle* physics)
      : world(v.loop, physics), standard(v.reference, params, v.loop, &world) {
    parts = standard.parts();
    run = std::make_unique<FlightRun>(v.reference, params, v.loop, parts);
  }
  enum class Phase { kFlying, kHolding, kDown };
  VehicleWorld world;
  StandardParts standard;
  FlightParts parts;
  std::unique_ptr<FlightRun> run;
  Phase phase = Phase::kFlying;
};

// The flight of member i has ended: its result, and what it does from now on (it holds its goal,
// or its rotors stop).
void Ended(Member* m, FlightResult* result) {
  *result = m->run->Finish();
  m->phase =
      result->status == FlightStatus::kReachedGoal ? Member::Phase::kHolding : Member::Phase::kDown;
}

// Each vehicle's push from the vehicles above it.
void ApplyDownwash(const std::vector<SwarmVehicle>& vehicles,
                   const std::vector<std::unique_ptr<Member>>& members, const SwarmParams& swarm) {
  for (size_t i = 0; i < members.size(); ++i) {
    Vec3 force = Vec3::Zero();
    const Vec3 lower = members[i]->world.Truth().p_W;
    for (size_t j = 0; j < members.size(); ++j) {
      if (j == i || members[j]->phase == Member::Phase::kDown) continue;
      force += DownwashForce(members[j]->world.Truth().p_W, lower,
                             vehicles[j].loop.vehicle->propeller_radius, swarm);
    }
    members[i]->world.SetInteractionForce(force);
  }
}

// The distances between the vehicles after a step at flight time `t` [s].
void MeasureSeparation(const std::vector<SwarmVehicle>& vehicles,
                       const std::vector<std::unique_ptr<Member>>& members, double t,
                       SwarmFlightResult* result) {
  for (size_t i = 0; i < members.size(); ++i) {
    const Vec3 p = members[i]->world.Truth().p_W;
    for (size_t j = i + 1; j < members.size(); ++j) {
      const double d = (members[j]->world.Truth().p_W - p).norm();
      result->vehicle_min_separation[i] = std::min(result->vehicle_min_separation[i], d);
      result->vehicle_min_separation[j] = std::min(result->vehicle_min_separation[j], d);
      if (d < result->min_separation) {
        result->min_separation = d;
        result->min_separation_time = t;
        result->closest_pair = vehicles[i].name + " and " + vehicles[j].name;
      }
    }
  }
}

}  // namespace

SwarmFlightResult FlySwarm(const std::vector<SwarmVehicle>& vehicles, const FlightParams& params,
                           const SwarmParams& swarm, Simulation* sim,
                           const std::function<void(double t)>& after_step) {
  params.Validate();
  swarm.Validate();
  if (static_cast<int>(vehicles.size()) != sim->vehicle_count()) {
    throw std::invalid_argument("FlySwarm: " + std::to_string(vehicles.size()) +
                                " vehicles for a world of " + std::to_string(sim->vehicle_count()));
  }
  std::vector<std::unique_ptr<Member>> members;
  for (size_t i = 0; i < vehicles.size(); ++i) {
    if (vehicles[i].loop.vehicle == nullptr || vehicles[i].loop.controller == nullptr) {
      throw std::invalid_argument("FlySwarm: " + vehicles[i].name +
                                  " has no vehicle or controller");
    }
    members.push_back(
        std::make_unique<Member>(vehicles[i], params, &sim->vehicle(static_cast<int>(i))));
  }
  SwarmFlightResult result;
  result.flights.resize(vehicles.size());
  result.vehicle_min_separation.assign(vehicles.size(), std::numeric_limits<double>::infinity());
  const double t0 = sim->time();
  for (long k = 0;; ++k) {
    // each vehicle's push from those above it, from where they are as the step begins
    if (swarm.downwash) ApplyDownwash(vehicles, members, swarm);
    bool flying = false;
    for (size_t i = 0; i < members.size(); ++i) {
      Member& m = *members[i];
      if (m.phase == Member::Phase::kFlying) {
        if (m.run->BeforePhysics(k)) {
          flying = true;
          continue;
        }
        Ended(&m, &result.flights[i]);
      }
      if (m.phase == Member::Phase::kHolding) m.run->HoldBeforePhysics(k);
    }
    if (!flying) break;
    for (size_t i = 0; i < members.size(); ++i) {
      const Member& m = *members[i];
      sim->vehicle(static_cast<int>(i))
          .SetCommands(m.phase == Member::Phase::kDown ? Vec4::Zero()
                                                       : Vec4(m.world.inner().mixer.thrusts));
    }
    sim->StepWorld();
    for (size_t i = 0; i < members.size(); ++i) {
      Member& m = *members[i];
      if (m.phase == Member::Phase::kFlying && !m.run->AfterPhysics()) {
        Ended(&m, &result.flights[i]);
      } else if (m.phase == Member::Phase::kHolding) {
        m.run->HoldAfterPhysics();
      }
    }
    MeasureSeparation(vehicles, members, sim->time() - t0, &result);
    if (after_step) after_step(sim->time() - t0);
  }
  for (const FlightResult& f : result.flights) result.time = std::max(result.time, f.time);
  return result;
}

Reference Delayed(const Reference& reference, double delay) {
  if (delay <= 0.0) return reference;
  Reference delayed;
  delayed.duration = reference.duration + delay;
  delayed.evaluate = [reference, delay](double t, int derivative) -> Vec3 {
    if (t >= delay) return reference.evaluate(t - delay, derivative);
    return derivative == kPosition ? reference.evaluate(0.0, kPosition) : Vec3::Zero();
  };
  if (reference.heading) {
    delayed.heading = [reference, delay](double t) -> std::pair<double, double> {
      if (t >= delay) return reference.heading(t - delay);
      return {reference.heading(0.0).first, 0.0};
    };
  }
  return delayed;
}

Conflict Check(const Reservation& a, const Reservation& b, double separation) {
  constexpr double kSample = 0.01;  // [s]
  const double required = a.radius + b.radius + separation;
  const double end = std::max(a.reference.duration, b.reference.duration);
  Conflict conflict;
  for (long k = 0;; ++k) {
    const double t = std::min(k * kSample, end);
    const Vec3 pa = a.reference.evaluate(std::min(t, a.reference.duration), kPosition);
    const Vec3 pb = b.reference.evaluate(std::min(t, b.reference.duration), kPosition);
    const double margin = (pa - pb).norm() - required;
    if (margin < conflict.margin) conflict = {margin, t};
    if (t >= end) break;
  }
  return conflict;
}

std::optional<double> ConflictFreeDelay(const Reservation& candidate,
                                        const std::vector<Reservation>& reserved,
                                        const SwarmParams& params) {
  const long steps = static_cast<long>(std::floor(params.max_wait / params.wait_step + 1e-9));
  for (long k = 0; k <= steps; ++k) {
    const double delay = k * params.wait_step;
    const Reservation delayed{Delayed(candidate.reference, delay), candidate.radius};
    const bool clear = std::all_of(reserved.begin(), reserved.end(), [&](const Reservation& r) {
      return Check(delayed, r, params.separation).margin >= 0.0;
    });
    if (clear) return delay;
  }
  return std::nullopt;
}

}  // namespace aerobox
