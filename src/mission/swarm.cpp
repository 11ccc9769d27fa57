#include "mission/swarm.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "common/stop.h"
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
  a.Number({"max_wait", "s", "... up to this, before a detour is tried"}, &max_wait, 0, 120);
  a.Number({"takeoff_time", "s",
            "a vehicle that starts on the floor climbs to its trajectory's start this long first"},
           &takeoff_time, 0, 30);
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
      : radius(VehicleRadius(*v.loop.vehicle)),
        world(v.loop, physics),
        params(v.flight.value_or(params)),
        standard(v.reference, this->params, v.loop, &world) {
    parts = standard.parts();
    run = std::make_unique<FlightRun>(v.reference, this->params, v.loop, parts);
  }
  enum class Phase { kFlying, kHolding, kDown };
  double radius;  // [m] for the clearance between vehicles
  VehicleWorld world;
  FlightParams params;
  StandardParts standard;
  FlightParts parts;
  std::unique_ptr<FlightRun> run;
  Phase phase = Phase::kFlying;
};

// The flight of member i has ended: its result, and what it does from now on: a vehicle that
// still flies holds its reference's end; one that crashed, or has no controller or no trusted
// state left, has its rotors cut.
void Ended(Member* m, FlightResult* result) {
  *result = m->run->Finish();
  switch (result->status) {
    case FlightStatus::kReachedGoal:
    case FlightStatus::kTimeout:
    case FlightStatus::kMissedGoal:
    case FlightStatus::kTerminated:
    case FlightStatus::kFlyAway:
      m->phase = Member::Phase::kHolding;
      break;
    default:
      m->phase = Member::Phase::kDown;
  }
}

// A holding vehicle that hit something: its flight ends as a collision now.
void HitWhileHolding(Member* m, const std::string& what, double t, FlightResult* result) {
  result->status = FlightStatus::kCollision;
  result->obstacle = what;
  result->time = t;
  result->end_position = m->world.Truth().p_W;
  m->phase = Member::Phase::kDown;
}

// Every vehicle's true state now, read once for the pairs below.
std::vector<State> Truths(const std::vector<std::unique_ptr<Member>>& members) {
  std::vector<State> states;
  for (const auto& m : members) states.push_back(m->world.Truth());
  return states;
}

// Each vehicle's push from the vehicles above it, in `states`.
void ApplyDownwash(const std::vector<SwarmVehicle>& vehicles,
                   const std::vector<std::unique_ptr<Member>>& members,
                   const std::vector<State>& states, const SwarmParams& swarm) {
  for (size_t i = 0; i < members.size(); ++i) {
    Vec3 force = Vec3::Zero();
    for (size_t j = 0; j < members.size(); ++j) {
      if (j == i || members[j]->phase == Member::Phase::kDown) continue;
      force += DownwashForce(states[j].p_W, states[i].p_W,
                             vehicles[j].loop.vehicle->propeller_radius, swarm);
    }
    // the model's push is along the lower vehicle's body z (gym-pybullet-drones applies it in
    // the body frame)
    members[i]->world.SetInteractionForce(states[i].q_WB * force);
  }
}

// The distances between the vehicles in `states`, after a step at flight time `t` [s].
void MeasureSeparation(const std::vector<SwarmVehicle>& vehicles,
                       const std::vector<std::unique_ptr<Member>>& members,
                       const std::vector<State>& states, double t, SwarmFlightResult* result) {
  for (size_t i = 0; i < members.size(); ++i) {
    for (size_t j = i + 1; j < members.size(); ++j) {
      const double d = (states[j].p_W - states[i].p_W).norm();
      const double gap = d - members[i]->radius - members[j]->radius;
      result->vehicle_min_separation[i] = std::min(result->vehicle_min_separation[i], d);
      result->vehicle_min_separation[j] = std::min(result->vehicle_min_separation[j], d);
      result->vehicle_min_clearance[i] = std::min(result->vehicle_min_clearance[i], gap);
      result->vehicle_min_clearance[j] = std::min(result->vehicle_min_clearance[j], gap);
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
  result.vehicle_min_clearance = result.vehicle_min_separation;
  const double t0 = sim->time();
  for (long k = 0;; ++k) {
    // each vehicle's push from those above it, from where they are as the step begins
    if (swarm.downwash) ApplyDownwash(vehicles, members, Truths(members), swarm);
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
        if (const std::optional<std::string> hit = m.run->HoldAfterPhysics()) {
          HitWhileHolding(&m, *hit, sim->time() - t0, &result.flights[i]);
        }
      }
    }
    MeasureSeparation(vehicles, members, Truths(members), sim->time() - t0, &result);
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

namespace {

constexpr double kSample = 0.01;  // [s] between the points a reservation is checked at

// A reservation's positions every kSample from t = 0 to its end (held there after it).
std::vector<Vec3> Sampled(const Reference& r) {
  std::vector<Vec3> p;
  const long n = static_cast<long>(std::ceil(r.duration / kSample - 1e-9));
  for (long k = 0; k <= n; ++k)
    p.push_back(r.evaluate(std::min(k * kSample, r.duration), kPosition));
  return p;
}

// The least margin [m] between `a` started `shift` samples late (at its start until then) and
// `b`, both held at their ends, beyond `required` [m] between centres; and when.
Conflict Margin(const std::vector<Vec3>& a, long shift, const std::vector<Vec3>& b,
                double required) {
  const long end = std::max(static_cast<long>(a.size()) + shift, static_cast<long>(b.size()));
  const auto at = [](const std::vector<Vec3>& p, long k) -> const Vec3& {
    return p[static_cast<size_t>(std::clamp(k, 0L, static_cast<long>(p.size()) - 1))];
  };
  Conflict conflict;
  for (long k = 0; k < end; ++k) {
    const double margin = (at(a, k - shift) - at(b, k)).norm() - required;
    if (margin < conflict.margin) conflict = {margin, k * kSample};
  }
  return conflict;
}

}  // namespace

Conflict Check(const Reservation& a, const Reservation& b, double separation) {
  return Margin(Sampled(a.reference), 0, Sampled(b.reference), a.radius + b.radius + separation);
}

std::optional<double> ConflictFreeDelay(const Reservation& candidate,
                                        const std::vector<Reservation>& reserved,
                                        const SwarmParams& params, double min_delay) {
  const std::vector<Vec3> own = Sampled(candidate.reference);
  std::vector<std::vector<Vec3>> others;
  for (const Reservation& r : reserved) others.push_back(Sampled(r.reference));
  const long step = std::max(1L, std::lround(params.wait_step / kSample));
  const long first = std::lround(std::ceil(min_delay / kSample - 1e-9));
  const long last = std::lround(std::floor(std::max(params.max_wait, min_delay) / kSample + 1e-9));
  for (long shift = first; shift <= last; shift += step) {
    ThrowIfStopRequested("planning several vehicles apart");
    bool clear = true;
    for (size_t i = 0; i < reserved.size() && clear; ++i) {
      clear =
          Margin(own, shift, others[i], candidate.radius + reserved[i].radius + params.separation)
              .margin >= 0.0;
    }
    if (clear) return shift * kSample;
  }
  return std::nullopt;
}

}  // namespace aerobox
