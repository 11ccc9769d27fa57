#include "mission/swarm_mission.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <memory>
#include <stdexcept>

#include "common/number_format.h"
#include "geometry/collision_world.h"
#include "mission/plan.h"
#include "scene/scene_mjcf.h"

namespace aerobox {

bool SwarmMissionResult::AllReached() const {
  return flight.AllReached() && std::all_of(schedule.begin(), schedule.end(),
                                            [](const SwarmSchedule& s) { return s.flies; });
}

namespace {

// At rest at `p` [m] for ever: a vehicle that holds its start.
Reference Parked(const Vec3& p) {
  Reference parked;
  parked.evaluate = [p](double, int derivative) {
    return derivative == kPosition ? p : Vec3::Zero();
  };
  return parked;
}

bool Planned(const PlanOutcome& plan) {
  return plan.result.status == PlanStatus::kSolved && plan.trajectory &&
         plan.trajectory->status == TrajectoryStatus::kSolved;
}

// The bends tried when waiting is not enough: the path through a point beside its middle, up,
// across (either side) or down, one to three separations away.
struct Bend {
  Vec3 offset;
  std::string words;
};
std::vector<Bend> Bends(const Vec3& start, const Vec3& goal, double step) {
  Vec3 across = Vec3::UnitZ().cross(goal - start);
  across = across.norm() > 1e-9 ? across.normalized() : Vec3::UnitX();
  std::vector<Bend> bends;
  for (int k = 1; k <= 3; ++k) {
    const double d = k * step;
    const std::string far = FormatNumber(std::round(d * 100) / 100) + " m ";
    bends.push_back({d * Vec3::UnitZ(), far + "up"});
    bends.push_back({d * across, far + "to the left"});
    bends.push_back({-d * across, far + "to the right"});
    bends.push_back({-d * Vec3::UnitZ(), far + "down"});
  }
  return bends;
}

// [s] before a vehicle's trajectory may start: the climb of one resting on the floor below it.
double TakeoffDelay(const FlightSetup& member, const PlanOutcome& plan, const SwarmParams& swarm) {
  const Vec3 rest = VehicleRestPosition(member.map, member.vehicle, member.start);
  return (plan.start.used - rest).norm() > 0.02 ? swarm.takeoff_time : 0.0;
}

// Vehicle i's schedule among the reservations of those before it: a wait (at least
// `min_delay` [s]), or a bent path and a wait (its plan then holds the bent path and
// trajectory; a mission through goals is not bent), or none.
SwarmSchedule ScheduleOne(const FlightSetup& member, PlanOutcome* plan,
                          const std::vector<Reservation>& before, const SwarmParams& swarm,
                          double min_delay, Reservation* reserved) {
  SwarmSchedule s;
  const double radius = VehicleRadius(member.vehicle);
  const Reservation own{ReferenceOf(plan->trajectory->trajectory), radius};
  s.duration = own.reference.duration;
  if (const std::optional<double> delay = ConflictFreeDelay(own, before, swarm, min_delay)) {
    s.flies = true;
    s.delay = *delay;
    *reserved = {Delayed(own.reference, *delay), radius};
    return s;
  }
  const Vec3 a = plan->start.used, b = plan->goal.used;
  const CollisionWorld world(member.map, member.PlannerCollision());
  const std::vector<Bend> bends =
      plan->via.empty() ? Bends(a, b, 1.5 * (2 * radius + swarm.separation)) : std::vector<Bend>();
  for (const Bend& bend : bends) {
    const Vec3 middle = 0.5 * (a + b) + bend.offset;
    if (!world.IsSegmentFree(a, middle) || !world.IsSegmentFree(middle, b)) continue;
    const std::vector<Vec3> path = {a, middle, b};
    TrajectoryResult bent = TrajectoryAlong(member, path);
    if (bent.status != TrajectoryStatus::kSolved) continue;
    const Reservation candidate{ReferenceOf(bent.trajectory), radius};
    const std::optional<double> delay = ConflictFreeDelay(candidate, before, swarm, min_delay);
    if (!delay) continue;
    s.flies = true;
    s.delay = *delay;
    s.detour = bend.words;
    s.duration = candidate.reference.duration;
    *reserved = {Delayed(candidate.reference, *delay), radius};
    plan->result.path = path;
    plan->trajectory = std::move(bent);
    return s;
  }
  s.note = "no plan keeps clear of the vehicles before it within " + FormatNumber(swarm.max_wait) +
           " s of waiting or a bend";
  return s;
}

// A vehicle that holds its start blocks those that would pass through it: they hold theirs too,
// until none does.
void HoldWhereBlocked(const FlightSetup& setup, std::vector<Reservation>* reserved,
                      SwarmMissionResult* result) {
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t i = 0; i < reserved->size(); ++i) {
      if (!result->schedule[i].flies) continue;
      for (size_t j = 0; j < reserved->size(); ++j) {
        if (j == i || result->schedule[j].flies) continue;
        if (Check((*reserved)[i], (*reserved)[j], setup.swarm.separation).margin >= 0.0) continue;
        result->schedule[i].flies = false;
        result->schedule[i].note =
            "would pass " + setup.vehicles[j].name + ", which holds its start";
        (*reserved)[i] = {Parked(result->plans[i].start.used), (*reserved)[i].radius};
        changed = true;
        break;
      }
    }
  }
}

// The schedule: each vehicle in the order given against those before it (prioritised), or each
// on its own ("none").
void Schedule(const FlightSetup& setup, const std::vector<FlightSetup>& members,
              SwarmMissionResult* result) {
  std::vector<Reservation> reserved;
  for (size_t i = 0; i < members.size(); ++i) {
    PlanOutcome& plan = result->plans[i];
    const double radius = VehicleRadius(members[i].vehicle);
    SwarmSchedule s;
    Reservation mine{Parked(plan.start.used), radius};
    if (!Planned(plan)) {
      s.note = plan.result.status != PlanStatus::kSolved ? "no path" : "no feasible trajectory";
    } else {
      const PiecewiseTrajectory& alone = plan.trajectory->trajectory;
      result->alone_makespan = std::max(result->alone_makespan, alone.duration());
      const double climb = TakeoffDelay(members[i], plan, setup.swarm);
      if (setup.swarm.planning == "none") {
        s.flies = true;
        s.delay = climb;
        s.duration = alone.duration();
        mine = {Delayed(ReferenceOf(alone), climb), radius};
      } else {
        s = ScheduleOne(members[i], &plan, reserved, setup.swarm, climb, &mine);
        if (!s.flies) mine = {Parked(plan.start.used), radius};
      }
    }
    result->schedule.push_back(s);
    reserved.push_back(mine);
  }
  if (setup.swarm.planning != "none") HoldWhereBlocked(setup, &reserved, result);
}

// The vehicles' flights in the world, from their plans and schedule.
struct Fleet {
  std::vector<std::unique_ptr<CollisionWorld>> worlds;
  std::vector<std::unique_ptr<Controller>> controllers;
  // with unknown boxes, each vehicle's own replanner (on the heap: the loops point at them)
  std::vector<std::unique_ptr<std::optional<Replanner>>> replanners;
  std::vector<SwarmVehicle> vehicles;
};

// Vehicle i's flight among the others: its reference (waiting, or holding its start), its
// controller and loop; the controller and the loop's clearance world go into `fleet`.
SwarmVehicle Flight(const FlightSetup& member, const PlanOutcome& plan, const SwarmSchedule& s,
                    std::uint64_t seed, const std::vector<MissionObserver*>& observers,
                    Fleet* fleet) {
  fleet->worlds.push_back(std::make_unique<CollisionWorld>(
      member.map, CollisionParams{member.vehicle.collision_size, 0.0}));
  fleet->controllers.push_back(MakeController(member.controller, member.vehicle));
  SwarmVehicle v;
  v.name = member.name;
  v.reference = s.flies ? Delayed(ReferenceOf(plan.trajectory->trajectory), s.delay)
                        : Parked(plan.start.used);
  v.loop = LoopFor(member, plan, fleet->controllers.back().get(), *fleet->worlds.back());
  v.loop.seed = seed;                  // each vehicle's own turbulence and sensor noise
  v.loop.shared_clock = true;          // the plans were kept apart on the world's clock
  if (!s.flies) v.loop.goals.clear();  // it holds its start: no mission to miss
  if (member.HasUnknown() && s.flies) {
    fleet->replanners.push_back(std::make_unique<std::optional<Replanner>>());
    AddReplanner(member, plan, fleet->replanners.back().get(), &v.loop);
  }
  if (!observers.empty()) {
    v.loop.telemetry = [observers](const TelemetrySample& sample) {
      for (MissionObserver* o : observers) o->OnSample(sample);
    };
  }
  return v;
}

// The world's observers' samples: the first vehicle's true state every control period of `rate`
// [Hz], through the whole flight.
std::function<void(double)> WorldSamples(const std::vector<MissionObserver*>& world,
                                         const Simulation& sim, double rate) {
  if (world.empty()) return {};
  return [&world, &sim, period = 1.0 / rate, next = 0.0](double t) mutable {
    if (t + 1e-9 < next) return;
    next += period;
    TelemetrySample sample;
    sample.t = t;
    sample.state = sim.vehicle(0).VehicleState();
    for (MissionObserver* o : world) o->OnSample(sample);
  };
}

// What the world's observers are told at the end: the first failure (its vehicle named with
// what it hit), or the first vehicle's arrival; timed at the last flight's end.
FlightResult WorldResult(const FlightSetup& setup, const SwarmFlightResult& flight) {
  FlightResult shown = flight.flights.front();
  for (size_t i = 0; i < flight.flights.size(); ++i) {
    const FlightResult& f = flight.flights[i];
    if (f.status == FlightStatus::kReachedGoal) continue;
    shown = f;
    shown.obstacle = setup.vehicles[i].name + (f.obstacle.empty() ? "" : " with " + f.obstacle);
    break;
  }
  shown.time = flight.time;
  return shown;
}

}  // namespace

SwarmMissionResult RunSwarm(const FlightSetup& setup, const SwarmParts& parts) {
  setup.Validate();
  if (setup.vehicles.empty()) throw std::invalid_argument("RunSwarm: the set-up has no vehicles");
  const size_t n = setup.vehicles.size();
  static const std::vector<MissionObserver*> kNone;
  const auto observers = [&](size_t i) -> const std::vector<MissionObserver*>& {
    return i < parts.observers.size() ? parts.observers[i] : kNone;
  };
  std::vector<FlightSetup> members, known;  // known: as each plans, without unknown boxes
  for (size_t i = 0; i < n; ++i) {
    members.push_back(setup.Member(i));
    known.push_back(Known(members.back()));
  }
  SwarmMissionResult result;
  for (const FlightSetup& member : known) {
    try {
      result.plans.push_back(PlanFlight(member));
    } catch (const InputError& e) {  // an unusable start or goal: named with its vehicle
      throw InputError(e.where(), "vehicles." + member.name + "." + e.field(), e.problem());
    }
  }
  Schedule(setup, known, &result);
  for (size_t i = 0; i < n; ++i) {
    for (MissionObserver* o : observers(i)) o->OnPlan(result.plans[i]);
  }

  std::vector<std::string> names;
  for (const SwarmMember& m : setup.vehicles) names.push_back(m.name);
  Simulation sim = Simulation::FromXml(SceneMjcfFor(setup), setup.name + " (scene)", names);
  for (MissionObserver* o : parts.world) o->OnScene(sim, {});
  for (MissionObserver* o : parts.world) o->OnPlan(result.plans.front());
  Fleet fleet;
  for (size_t i = 0; i < n; ++i) {
    PlaceVehicleAtStart(setup.map, members[i].vehicle, members[i].start, result.plans[i].start.used,
                        &sim.vehicle(static_cast<int>(i)));
    fleet.vehicles.push_back(Flight(members[i], result.plans[i], result.schedule[i], setup.seed + i,
                                    observers(i), &fleet));
    for (MissionObserver* o : observers(i)) o->OnFlightStart(sim, *fleet.controllers.back());
  }
  for (MissionObserver* o : parts.world) o->OnFlightStart(sim, *fleet.controllers.front());
  const auto wall = std::chrono::steady_clock::now();
  result.flight = FlySwarm(fleet.vehicles, setup.flight, setup.swarm, &sim,
                           WorldSamples(parts.world, sim, members.front().controller.rate));
  result.flight_wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
  for (size_t i = 0; i < n; ++i) {
    const SwarmSchedule& s = result.schedule[i];
    if (s.flies) result.makespan = std::max(result.makespan, s.delay + s.duration);
    const FlightResult& f = result.flight.flights[i];
    if (s.flies && f.status == FlightStatus::kReachedGoal) {
      result.flown_makespan = std::max(result.flown_makespan, f.time);
    }
    for (MissionObserver* o : observers(i)) o->OnFlightEnd(sim, result.flight.flights[i]);
  }
  for (MissionObserver* o : parts.world) o->OnFlightEnd(sim, WorldResult(setup, result.flight));
  return result;
}

}  // namespace aerobox
