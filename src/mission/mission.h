// A run as a composition (after RotorPy's Environment and Drake's diagrams): a set-up (world,
// vehicle, planner and trajectory settings, controller, flight settings) and observers in; a
// status and the result out. Planning, the trajectory, the scene and the closed loop are
// composed here; what is written, drawn or printed is the observers' business. No command
// line, TOML or files inside.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "control/controller.h"
#include "geometry/collision_world.h"
#include "mission/flight.h"
#include "mission/plan.h"
#include "mission/setup.h"
#include "sim/simulation.h"

namespace aerobox {

struct DepthImage;    // perception/depth_camera.h
class OccupancyGrid;  // perception/occupancy_grid.h

// Told what happens, in this order; every call may throw to stop the run (the exception
// leaves RunMission after the scene thread has been joined).
class MissionObserver {
 public:
  virtual ~MissionObserver() = default;
  // The scene is loaded. A small map's scene does not depend on the plan, so this runs on a
  // second thread while the planner works (it must touch nothing else); the scene of a city or
  // of a map with many boxes keeps only the boxes near the route (`kept`, one flag per map box;
  // empty: all), so it comes after the plan, on the calling thread.
  virtual void OnScene(Simulation&, const std::vector<bool>& /*kept*/) {}
  // The path and the trajectory, or the status that stopped them.
  virtual void OnPlan(const PlanOutcome&) {}
  // The vehicle sits at its start; the controller is about to fly.
  virtual void OnFlightStart(const Simulation&, const Controller&) {}
  // One per control step.
  virtual void OnSample(const TelemetrySample&) {}
  virtual void OnFlightEnd(const Simulation&, const FlightResult&) {}
  // With unknown boxes, before each OnSample: when each box was revealed so far ([s]; < 0: not
  // yet or known from the start), and every replan so far.
  virtual void OnDiscovery(const std::vector<double>& /*revealed_at*/,
                           const std::vector<ReplanEvent>& /*replans*/) {}
  // With a depth camera, before the OnSample after each new frame: the frame and the occupancy
  // map it was fused into, at flight time `t` [s].
  virtual void OnDepthFrame(double /*t*/, const DepthImage& /*image*/,
                            const OccupancyGrid& /*map*/) {}
};

enum class MissionStatus { kReachedGoal, kNoPath, kNoTrajectory, kFlightFailed };
const char* ToString(MissionStatus status);

struct MissionResult;
// How a run ended, in words: the flight's status and the obstacle it hit ("collision with
// block_3"), or the mission's status when it did not fly ("no path").
std::string Outcome(const MissionResult& result);

struct MissionResult {
  MissionStatus status = MissionStatus::kNoPath;
  PlanOutcome plan;
  bool flown = false;
  FlightResult flight;            // when flown
  double flight_wall_time = 0.0;  // [s]
  // with unknown boxes: every replan, and when each box was revealed ([s]; < 0: never)
  std::vector<ReplanEvent> replans;
  std::vector<double> revealed_at;
  std::vector<double> revealed_distance;  // [m] from the sensor at that moment (< 0: never)
  int unknown_boxes = 0;
  int revealed_boxes = 0;
  // with a depth camera: the occupancy map at the end of the flight, and where the camera's
  // time went
  struct Occupancy {
    std::shared_ptr<const OccupancyGrid> grid;
    SensingCost cost;
  };
  std::optional<Occupancy> occupancy;
};

struct MissionParts {
  // The controller; nullptr: the one setup.controller.kind names, from the registry.
  Controller* controller = nullptr;
  std::vector<MissionObserver*> observers;  // not owned
};

// Buildings (boxes) farther than this from a city flight's trajectory are left out of its
// scene [m]: see RunMission. The same holds for any map with more than kCullAboveBoxes boxes
// (a 5000-tree forest costs MuJoCo as much as the city).
inline constexpr double kCityRouteMargin = 25.0;
inline constexpr size_t kCullAboveBoxes = 500;

// The closed loop's parts from the set-up: the vehicle, the controller at its rate, the
// clearance (`world` must outlive the loop), the air and the sensors, a mission's goals.
FlightLoop LoopFor(const FlightSetup& setup, const PlanOutcome& plan, Controller* controller,
                   const CollisionWorld& world);

// Boxes found in flight (setup.HasUnknown()): a replanner, made into `replanner`, that senses
// them and replans around them through the flight's planner (a given path cannot be replanned
// by itself: RRT* then), as the loop's update_reference (and map_size with a depth camera).
void AddReplanner(const FlightSetup& setup, const PlanOutcome& plan,
                  std::optional<Replanner>* replanner, FlightLoop* loop);

// The set-up as the vehicle knows its map before take-off: without its unknown boxes (what it
// plans on).
FlightSetup Known(const FlightSetup& setup);

// Plans, solves, loads the scene, places the vehicle and flies. Throws InputError for unusable
// endpoints and std::invalid_argument for bad settings; a missing path, trajectory or a failed
// flight is a status.
MissionResult RunMission(const FlightSetup& setup, const MissionParts& parts);

}  // namespace aerobox
