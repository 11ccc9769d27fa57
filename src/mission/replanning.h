// Obstacles discovered in flight: boxes the planner does not know, a range sensor that reveals
// them, and replanning when a revealed box blocks the rest of the trajectory. MuJoCo has every
// box from the start, so a box seen too late is a real collision.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/schema.h"
#include "geometry/collision_world.h"
#include "map/map.h"
#include "mission/flight.h"
#include "perception/depth_camera.h"
#include "perception/occupancy_grid.h"
#include "planning/planner.h"
#include "trajectory/generators.h"
#include "trajectory/trajectory_generator.h"

namespace aerobox {

// What finds the unknown boxes in flight, at the sensor's rate:
// - kOmni: a box is revealed whole when any part of it is within range;
// - kCamera: ... within range and the field of view around the body's x axis; for both, nothing
//   occludes (a box behind another is seen too), and the planner then knows the whole box;
// - kDepth: a depth camera (perception/depth_camera.h) whose rays stop at the first surface;
//   its points build an occupancy map (perception/occupancy_grid.h), and the planner avoids the
//   map's occupied cells, not the boxes: unknown space counts as free (optimistic), and the speed
//   cap keeps the vehicle able to stop within what the camera sees.
struct SensingParams {
  enum class Kind { kOmni, kCamera, kDepth };
  Kind kind = Kind::kOmni;
  double range = 3.0;              // [m]
  double fov_horizontal = 1.5184;  // [rad] 87 deg (an Intel RealSense D435's depth field)
  double fov_vertical = 1.0123;    // [rad] 58 deg
  double rate = 25.0;              // [Hz] divides the controller's rate (so the physics rate)
  DepthCameraParams camera;        // kDepth: size, mounting, noise
  OccupancyParams map;             // kDepth: the occupancy map's resolution

  void Describe(Archive& a);  // [sensing] (common/schema.h)
  void Validate() const;      // throws std::invalid_argument naming the field
  // The depth camera's parameters, with the field of view and range of [sensing].
  DepthCameraParams Camera() const;
};

// Replanning in flight: from the reference `horizon` seconds ahead of the vehicle, RRT* per leg
// to iteration counts (`search_iterations` for a first solution, then `iterations` more), so
// that the same seed replans the same on any machine under any load; `time_budget` of wall time
// is only a safety cap, and a search it cuts is reported (ReplanEvent::time_capped). Then a
// trajectory that continues the reference's state.
struct ReplanParams {
  double horizon = 0.3;           // [s]
  long iterations = 300;          // RRT* iterations after the first solution, per leg
  long search_iterations = 3000;  // RRT* iterations for a first solution, per leg, at most
  double time_budget = 2.0;       // [s] of wall time per leg: a safety cap, not the budget
  int max_attempts = 50;          // attempts while braked before the flight gives up

  void Describe(Archive& a);  // [replan] (common/schema.h)
  void Validate() const;
};

// Where a depth camera's time goes [s of wall time, summed over the flight].
struct SensingCost {
  int frames = 0;
  double capture = 0.0;  // ray casting the depth images
  double fusion = 0.0;   // into the occupancy map
  double rebuild = 0.0;  // the planner's world from the occupied cells
};

// One replan: when, what triggered it, how long it took, what came of it.
struct ReplanEvent {
  double t = 0.0;               // [s] of flight when the blocking box was found
  std::string trigger;          // the box that blocked the trajectory (its map name)
  double planning_time = 0.0;   // [s] wall, RRT*
  double solve_time = 0.0;      // [s] wall, the trajectory
  double latency = 0.0;         // [s] wall, trigger to the new trajectory ready
  double path_length = 0.0;     // [m] of the new path
  bool time_capped = false;     // the wall-time cap cut a search: not reproducible by seed
  std::string outcome;          // "replanned", "braking", "no path", ...
  std::vector<Vec3> abandoned;  // the rest of the path given up [m]
  // the trajectory that replaced it, every 0.05 s from where it joins [m] and its speed [m/s]
  // (empty when nothing replaced it)
  std::vector<Vec3> replacement;
  std::vector<double> replacement_speeds;
};

// The deceleration a braking vehicle may count on [m/s^2]: 60 % of what its tilt limit gives,
// the rest kept for the controller.
double BrakingDeceleration(double max_tilt);

// The fastest a vehicle may fly and still stop before a box its sensor has just revealed [m/s]:
// v^2 / (2 a) + v tau = range - margin, with tau the sensor's period, the replanning horizon and
// 0.1 s for the replan itself, a the braking deceleration and margin the vehicle's half size and
// clearance.
double SensingSpeedLimit(const SensingParams& sensing, const ReplanParams& replan,
                         double deceleration, double margin);

// Which of a map's boxes are unknown: the listed indices, or a seeded draw of `fraction` of
// them (rounded); throws std::invalid_argument for an index outside the map.
std::vector<bool> UnknownBoxes(const Map& map, const std::vector<int>& indices, double fraction,
                               std::uint64_t seed);

// The map without its unknown boxes: what the planner knows before take-off.
Map KnownMap(const Map& map, const std::vector<bool>& unknown);

// True when the sensor at `state` sees any part of `box` [m].
bool SeesBox(const SensingParams& sensing, const State& state, const Aabb& box);

// The loop's reference updater (FlightLoop::update_reference): senses at its rate, and when a
// newly revealed box blocks the reference's rest, plans and splices a continuation, or brakes
// and keeps trying. With a depth camera, unknown space is free to the planner, but each new
// reference ends at rest before the first point of its path where the vehicle (grown by its
// clearance) would overlap a cell the camera has not seen, and is extended as the camera sees
// further: the vehicle can always stop within what it has seen.
class Replanner {
 public:
  // `planning` and `trajectory`: the collision parameters of the planner and of trajectories;
  // `planner` (through the Planner seam: a user's planner replans too) and `generator` (through
  // the TrajectoryGenerator seam's Continue; min-snap's when it cannot start in motion) as the
  // flight's planning uses them, RRT*'s counts replaced by [replan]'s; `goals`: the mission's
  // goals in order, the last one where the reference ends; `path`: the planned path the
  // reference flies. A blocked path is repaired locally first: the planner from the vehicle's
  // state to the first point of the path beyond the blocked stretch from which the rest is free,
  // then the rest; only when that fails, the planner through all the goals still ahead.
  Replanner(const Map& map, const std::vector<bool>& unknown, const CollisionParams& planning,
            const CollisionParams& trajectory, const PlannerConfig& planner,
            const GeneratorConfig& generator, const SensingParams& sensing,
            const ReplanParams& replan, std::vector<Vec3> goals, std::vector<Vec3> path,
            std::uint64_t seed);

  // Called at each control step with the reference's time, the vehicle's state (as the
  // controller sees it), how many goals it has reached and the current reference; returns a
  // new reference when it replanned.
  std::optional<Reference> Update(double t, double tr, const State& state, int goals_reached,
                                  const Reference& current);

  const std::vector<ReplanEvent>& events() const { return events_; }
  // [s] of flight when each box was revealed (negative: known from the start or never seen);
  // with a depth camera, when a ray first hit it
  const std::vector<double>& revealed_at() const { return revealed_at_; }
  // [m] from the sensor when each box was revealed (negative: not revealed): with a depth
  // camera, the nearest of the first frame's points on it; else the nearest point of the box
  const std::vector<double>& revealed_distance() const { return revealed_distance_; }
  // kDepth: the occupancy map (nothing for the other kinds)
  std::shared_ptr<const OccupancyGrid> occupancy() const { return grid_; }
  // kDepth: the camera's last frame (nothing before the first)
  std::shared_ptr<const DepthImage> depth_image() const { return depth_image_; }
  const SensingCost& cost() const { return cost_; }
  int unknown_count() const;
  int revealed_count() const;

 private:
  std::optional<Reference> Replan(double t, double tr, int goals_reached, const Reference& current,
                                  const std::string& trigger);
  // The first point of the reference after `tr` where it leaves free space.
  std::optional<Vec3> FirstBlocked(const Reference& current, double tr) const;
  // The name of the box among `newly` (all revealed when empty) nearest `p`.
  std::string TriggerNear(const Vec3& p, std::vector<size_t> newly) const;
  // kDepth: true when the reference from `from` [s], within the distance a vehicle at `speed`
  // [m/s] needs to stop, passes a cell the camera has not seen.
  bool UnknownAhead(const Reference& reference, double from, double speed) const;
  // Whether the depth camera has seen every cell the vehicle's box overlaps at `p` [m].
  bool Seen(const Vec3& p) const;
  // kDepth: the first point along `path` between `from` and `to` [m of its length] (every
  // kWalkStep) where the vehicle's box would overlap an unseen cell, or with `blocked`, where
  // the trajectory's world is not free (and *blocked set); infinity when none.
  double FirstUnseen(const std::vector<Vec3>& path, double from, double to,
                     bool* blocked = nullptr) const;
  // kDepth: the camera now sees kExtend of the path beyond where the reference ends (or the
  // reference is the flight's first, not yet cut to what was seen); the vehicle at `p` [m].
  bool SeenFurther(const Vec3& p) const;
  // A path from `start` through the goals still ahead: first the local repair, then leg by leg.
  std::optional<std::vector<Vec3>> FindPath(const Vec3& start, int goals_reached,
                                            ReplanEvent* event) const;
  // The vertex of the current path the local repair rejoins (its size: none).
  size_t Rejoin(const Vec3& start, int goals_reached) const;
  // A stop along the direction of travel: one the known world has room for, or else the one at
  // the braking distance regardless (nothing only when no trajectory reaches either).
  std::optional<PiecewiseTrajectory> Brake(const StartState& start) const;
  static void ReplacedBy(const PiecewiseTrajectory& trajectory, ReplanEvent* event);
  // One reading at `t`: the boxes it revealed first; true when what the planner avoids changed.
  bool Sense(double t, const State& state, std::vector<size_t>* newly);
  bool SenseDepth(double t, const State& state, std::vector<size_t>* newly);
  // The trajectory from `start` along `path`, through the seam; inside `escape` [m], anything
  // goes (a vehicle backing off from cells it stopped too near).
  TrajectoryResult Continue(const StartState& start, const std::vector<Vec3>& path,
                            const std::optional<Aabb>& escape = std::nullopt) const;
  // The nearest point to `p` (within 0.4 m, in 26 directions) where the trajectory's world is
  // free.
  std::optional<Vec3> NearestFree(const Vec3& p) const;
  // A path from `start` through the goals still ahead and the trajectory along it (nothing when
  // no path or no trajectory was found; `event` gets the times and the last path's length).
  struct Continuation {
    std::vector<Vec3> path;
    PiecewiseTrajectory trajectory;
    double committed;  // [m] along `path` where the trajectory ends (infinity: at its end)
  };
  std::optional<Continuation> Continue(const StartState& start, int goals_reached,
                                       ReplanEvent* event) const;

  Map map_;
  std::vector<bool> unknown_;
  std::vector<bool> known_;
  CollisionParams planning_;
  CollisionParams trajectory_;
  PlannerConfig planner_;
  TrajectoryParams params_;                         // the generator's
  std::unique_ptr<TrajectoryGenerator> generator_;  // the flight's
  std::unique_ptr<TrajectoryGenerator> minsnap_;    // where the flight's cannot start in motion
  SensingParams sensing_;
  ReplanParams replan_;
  std::vector<Vec3> goals_;
  std::vector<Vec3> path_;  // the path the reference flies, updated with each replan
  // kDepth: [m] along path_ where the reference ends, before what the camera had not seen
  // (infinity: at the path's end; nothing: the flight's first reference, not yet cut)
  std::optional<double> committed_;
  std::uint64_t seed_;
  std::vector<double> revealed_at_;
  std::vector<double> revealed_distance_;
  std::vector<Aabb> extents_;            // every box of the map: what the depth camera sees
  std::optional<DepthCamera> camera_;    // kDepth
  std::shared_ptr<OccupancyGrid> grid_;  // kDepth
  std::shared_ptr<const DepthImage> depth_image_;  // kDepth: the last frame
  SensingCost cost_;
  std::optional<CollisionWorld> planner_world_, trajectory_world_;
  double next_sense_ = 0.0;
  bool braking_ = false;  // the last attempt found nothing: the reference brakes to a stop
  int attempts_ = 0;
  bool retried_still_ = false;  // the last attempt while braked was made at rest ...
  long known_at_retry_ = 0;     // ... knowing this many cells (or boxes)
  std::vector<ReplanEvent> events_;
  void Rebuild();
};

}  // namespace aerobox
