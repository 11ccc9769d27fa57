#include "mission/mission.h"

#include <chrono>
#include <future>
#include <optional>

#include "common/stop.h"
#include "geometry/collision_world.h"
#include "scene/scene_mjcf.h"

namespace aerobox {

const char* ToString(MissionStatus status) {
  switch (status) {
    case MissionStatus::kReachedGoal:
      return "reached goal";
    case MissionStatus::kNoPath:
      return "no path";
    case MissionStatus::kNoTrajectory:
      return "no feasible trajectory";
    case MissionStatus::kFlightFailed:
      return "flight failed";
  }
  return "?";
}

std::string Outcome(const MissionResult& result) {
  if (!result.flown) return ToString(result.status);
  std::string why = ToString(result.flight.status);
  if (!result.flight.obstacle.empty()) why += " with " + result.flight.obstacle;
  return why;
}

namespace {

// The trajectory's points every 0.1 s and the vehicle's resting start: what the route of a city
// flight passes.
std::vector<Vec3> Route(const FlightSetup& setup, const PiecewiseTrajectory& trajectory) {
  std::vector<Vec3> route;
  for (double t = 0; t <= trajectory.duration(); t += 0.1) {
    route.push_back(trajectory.Evaluate3(t, kPosition));
  }
  route.push_back(trajectory.Evaluate3(trajectory.duration(), kPosition));
  route.push_back(VehicleRestPosition(setup.map, setup.vehicle, setup.start));
  return route;
}

// How often waiting for the scene thread looks for a stop request.
constexpr std::chrono::milliseconds kSceneWaitPoll{10};

// The plan, made while the scene loads on its own thread (joined on every way out); a Ctrl-C
// while the scene thread is still inside MuJoCo's GL set-up ends the process at once.
PlanOutcome PlanWhileSceneLoads(const FlightSetup& setup, std::future<void>* scene) {
  PlanOutcome plan;
  try {
    plan = PlanFlight(Known(setup));  // the planner knows only the boxes that are not unknown
  } catch (const Interrupted& stop) {
    // Ctrl-C while the scene thread is still inside MuJoCo's GL set-up (mjr_makeContext: about
    // 0.3 s of texture set-up on a CPU renderer), which nothing can stop: rather than wait for
    // it, the process ends here, its temporary files removed
    if (scene->valid() && scene->wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
      ExitInterrupted(stop.during());
    }
    throw;
  } catch (...) {
    if (scene->valid()) scene->wait();
    throw;
  }
  // the scene may still be loading (and its renderer compiling its shaders): a Ctrl-C meanwhile
  // ends the process at once, as above
  while (scene->valid() && scene->wait_for(kSceneWaitPoll) != std::future_status::ready) {
    if (StopRequested()) ExitInterrupted("loading the scene");
  }
  if (scene->valid()) scene->get();  // rethrows what loading the scene threw
  return plan;
}

// What the replanner found: its replans, when and how far away each box was first seen, the
// occupancy map.
void TakeDiscovery(const Replanner& replanner, MissionResult* result) {
  result->replans = replanner.events();
  result->revealed_at = replanner.revealed_at();
  result->revealed_distance = replanner.revealed_distance();
  if (replanner.occupancy()) {
    result->occupancy = MissionResult::Occupancy{replanner.occupancy(), replanner.cost()};
  }
  result->unknown_boxes = replanner.unknown_count();
  result->revealed_boxes = replanner.revealed_count();
}

}  // namespace

void AddReplanner(const FlightSetup& setup, const PlanOutcome& plan,
                  std::optional<Replanner>* replanner, FlightLoop* loop) {
  std::vector<Vec3> goals = loop->goals;
  goals.push_back(plan.goal.used);
  PlannerConfig planner = PlannerConfigFor(setup);
  if (planner.kind == "waypoints") planner.kind = "rrt_star";
  GeneratorConfig generator;  // the flight's, as TrajectoryAlong makes it
  generator.method = setup.planning.trajectory_method;
  generator.params = TrajectoryParamsFor(setup);
  generator.given = setup.planning.given_trajectory;
  replanner->emplace(setup.map, setup.unknown, setup.PlannerCollision(),
                     setup.TrajectoryCollision(), planner, generator, setup.sensing, setup.replan,
                     goals, plan.result.path, setup.seed);
  loop->update_reference = [replanner](double t, double tr, const State& state, int reached,
                                       const Reference& current) {
    return (*replanner)->Update(t, tr, state, reached, current);
  };
  if (setup.sensing.kind == SensingParams::Kind::kDepth) {
    loop->map_size = [replanner]() {
      const OccupancyGrid& grid = *(*replanner)->occupancy();
      return OccupancySize{grid.occupied_count(), grid.free_count()};
    };
  }
}

FlightSetup Known(const FlightSetup& setup) {
  if (!setup.HasUnknown()) return setup;
  FlightSetup known = setup;
  known.map = KnownMap(setup.map, setup.unknown);
  return known;
}

FlightLoop LoopFor(const FlightSetup& setup, const PlanOutcome& plan, Controller* controller,
                   const CollisionWorld& world) {
  FlightLoop loop;
  loop.vehicle = &setup.vehicle;
  loop.controller = controller;
  loop.control_rate = setup.controller.rate;
  loop.nonfinite_setpoint_from = setup.faults.nonfinite_setpoint_from;
  loop.inner = setup.controller.inner;
  loop.clearance = [&world](const Vec3& p) { return world.Clearance(p); };
  AddAirAndSensors(setup, &loop);
  for (const Endpoint& goal : plan.via) loop.goals.push_back(goal.used);
  loop.stop_at_goals = setup.stop_at_goals;
  return loop;
}

MissionResult RunMission(const FlightSetup& setup, const MissionParts& parts) {
  setup.Validate();
  if (!setup.vehicles.empty()) {
    throw std::invalid_argument("RunMission flies one vehicle: RunSwarm flies [[vehicles]]");
  }
  std::unique_ptr<Simulation> sim;
  const auto load_scene = [&](const std::vector<bool>& kept) {
    sim = std::make_unique<Simulation>(
        Simulation::FromXml(SceneMjcfFor(setup, kept), setup.name + " (scene)"));
    for (MissionObserver* observer : parts.observers) observer->OnScene(*sim, kept);
  };
  // a city, or any map with many boxes: the scene keeps the boxes near the route only
  const bool cull = IsCityScale(setup.map) || setup.map.boxes.size() > kCullAboveBoxes;
  std::future<void> scene;
  if (!cull) scene = std::async(std::launch::async, load_scene, std::vector<bool>());

  // plan and solve while the scene loads
  MissionResult result;
  result.plan = PlanWhileSceneLoads(setup, &scene);
  const PlanOutcome& plan = result.plan;
  for (MissionObserver* observer : parts.observers) observer->OnPlan(plan);
  if (plan.result.status != PlanStatus::kSolved) {
    result.status = MissionStatus::kNoPath;
    return result;
  }
  if (plan.trajectory->status != TrajectoryStatus::kSolved) {
    result.status = MissionStatus::kNoTrajectory;
    return result;
  }
  const PiecewiseTrajectory& trajectory = plan.trajectory->trajectory;
  if (cull) {
    // MuJoCo 2.2 tests the vehicle against every geom of the world body at each step: 3845
    // buildings make a step 60 times dearer. The flight is lost (fly-away) once it is
    // flyaway_distance from its setpoint, so buildings farther than kCityRouteMargin from the
    // trajectory cannot be reached; they are drawn, not simulated. Clearance is still measured
    // against every box.
    if (!(setup.flight.flyaway_distance < kCityRouteMargin)) {
      throw std::invalid_argument("FlightParams.flyaway_distance must stay below " +
                                  std::to_string(kCityRouteMargin) + " m in a large map");
    }
    load_scene(RouteBoxes(setup.map, Route(setup, trajectory), kCityRouteMargin));
  }

  // fly: the vehicle rests at the start (on the floor when the start is at floor level)
  PlaceVehicleAtStart(setup.map, setup.vehicle, setup.start, plan.start.used, sim.get());
  const CollisionWorld world(setup.map, CollisionParams{setup.vehicle.collision_size, 0.0});
  std::unique_ptr<Controller> made;
  Controller* controller = parts.controller;
  if (controller == nullptr) {
    made = MakeController(setup.controller, setup.vehicle);
    controller = made.get();
  }
  for (MissionObserver* observer : parts.observers) observer->OnFlightStart(*sim, *controller);
  FlightLoop loop = LoopFor(setup, plan, controller, world);
  std::optional<Replanner> replanner;
  if (setup.HasUnknown()) AddReplanner(setup, plan, &replanner, &loop);
  if (!parts.observers.empty()) {
    loop.telemetry = [&parts, &replanner, frames = 0](const TelemetrySample& s) mutable {
      const bool new_frame = replanner && replanner->cost().frames != frames;
      if (new_frame) frames = replanner->cost().frames;
      for (MissionObserver* observer : parts.observers) {
        if (new_frame && replanner->depth_image()) {
          observer->OnDepthFrame(s.t, *replanner->depth_image(), *replanner->occupancy());
        }
        if (replanner) observer->OnDiscovery(replanner->revealed_at(), replanner->events());
        observer->OnSample(s);
      }
    };
  }
  const auto begin = std::chrono::steady_clock::now();
  result.flight = FlyTrajectory(ReferenceOf(trajectory), setup.flight, loop, sim.get());
  result.flight_wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  result.flown = true;
  if (replanner) TakeDiscovery(*replanner, &result);
  result.status = result.flight.status == FlightStatus::kReachedGoal ? MissionStatus::kReachedGoal
                                                                     : MissionStatus::kFlightFailed;
  for (MissionObserver* observer : parts.observers) observer->OnFlightEnd(*sim, result.flight);
  return result;
}

}  // namespace aerobox
