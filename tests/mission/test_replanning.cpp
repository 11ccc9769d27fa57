// Obstacles discovered in flight: which boxes are unknown, what the sensor sees, and a flight
// that replans around a wall it did not know.
#include <doctest/doctest.h>

#include <stdexcept>

#include "mission/mission.h"
#include "mission/replanning.h"
#include "planning/planner.h"
#include "planning/rrt_star.h"
#include "trajectory/generators.h"

namespace aerobox {
namespace {

Map Room(bool with_wall) {
  Map map;
  map.name = "room";
  map.bounds = {Vec3(0, 0, 0), Vec3(12, 8, 3)};
  if (with_wall)
    map.boxes.push_back({{Vec3(5.5, 0, 0), Vec3(6, 5.5, 3)}, Vec3(1, 0, 0), "wall", 1});
  map.boxes.push_back({{Vec3(9, 6.5, 0), Vec3(10, 8, 3)}, Vec3(0, 1, 0), "corner", 2});
  return map;
}

FlightSetup RoomSetup(std::uint64_t seed) {
  FlightSetup setup;
  setup.name = "room";
  setup.map = Room(true);
  setup.start = Vec3(1, 2, 1);
  setup.start_origin = "test";
  setup.goal = Vec3(11, 2, 1);
  setup.goal_origin = "test";
  setup.seed = seed;
  setup.unknown = {true, false};  // the wall across the way
  return setup;
}

}  // namespace

TEST_CASE("unknown boxes: by index, by a seeded share, and the map the planner knows") {
  Map map = Room(true);
  for (int i = 0; i < 8; ++i) map.boxes.push_back(map.boxes[1]);
  CHECK(UnknownBoxes(map, {0, 3}, 0.0, 1) ==
        std::vector<bool>{true, false, false, true, false, false, false, false, false, false});
  const std::vector<bool> a = UnknownBoxes(map, {}, 0.3, 7);
  CHECK(std::count(a.begin(), a.end(), true) == 3);
  CHECK(a == UnknownBoxes(map, {}, 0.3, 7));  // the same seed, the same boxes
  bool differs = false;
  for (std::uint64_t seed = 8; seed < 20 && !differs; ++seed) {
    differs = UnknownBoxes(map, {}, 0.3, seed) != a;
  }
  CHECK(differs);
  CHECK_THROWS_AS(UnknownBoxes(map, {10}, 0.0, 1), std::invalid_argument);
  CHECK(KnownMap(map, a).boxes.size() == 7);
}

TEST_CASE("the range sensor sees a box in range, the camera only in its field of view") {
  const Aabb box{Vec3(2, -0.5, 0), Vec3(3, 0.5, 2)};
  State s;
  s.p_W = Vec3(0, 0, 1);
  SensingParams omni;
  omni.range = 3.0;
  CHECK(SeesBox(omni, s, box));  // its near face is 2 m away
  omni.range = 1.5;
  CHECK_FALSE(SeesBox(omni, s, box));
  SensingParams camera;
  camera.kind = SensingParams::Kind::kCamera;
  camera.range = 3.0;
  CHECK(SeesBox(camera, s, box));                         // straight ahead
  s.q_WB = Quat(Eigen::AngleAxisd(M_PI, Vec3::UnitZ()));  // facing away
  CHECK_FALSE(SeesBox(camera, s, box));
  s.q_WB = Quat(Eigen::AngleAxisd(0.6, Vec3::UnitZ()));  // 34 degrees off: the box's edge in view
  CHECK(SeesBox(camera, s, box));
}

TEST_CASE("a wall the planner did not know is seen, flown around, and the same seed repeats") {
  const MissionResult first = RunMission(RoomSetup(3), MissionParts());
  CAPTURE(ToString(first.flight.status));
  REQUIRE(first.status == MissionStatus::kReachedGoal);
  CHECK(first.flight.status == FlightStatus::kReachedGoal);  // no contact on the way
  CHECK(first.unknown_boxes == 1);
  CHECK(first.revealed_boxes == 1);
  REQUIRE_FALSE(first.replans.empty());
  CHECK(first.replans.front().trigger == "wall");
  for (const ReplanEvent& e : first.replans)
    MESSAGE(e.t << " s " << e.trigger << ": " << e.outcome);
  // at once, or after braking when no continuation was found in time
  CHECK(first.replans.back().outcome.find("replanned") != std::string::npos);
  CHECK(first.replans.back().path_length > 8.0);  // around the wall, not through it
  CHECK_FALSE(first.replans.front().abandoned.empty());
  CHECK(first.flight.replans == static_cast<int>(first.replans.size()));
  // the planned path went through the wall: the planner did not know it
  bool through = false;
  for (const Vec3& p : first.plan.result.path) through |= p.y() < 5.5 && p.x() > 5 && p.x() < 6.5;
  CHECK((through || first.plan.result.path.size() == 2));
  const MissionResult again = RunMission(RoomSetup(3), MissionParts());
  REQUIRE(again.replans.size() == first.replans.size());
  CHECK(again.revealed_at == first.revealed_at);
  CHECK(again.flight.time == first.flight.time);
  // known from the start: nothing to replan
  FlightSetup known = RoomSetup(3);
  known.unknown.clear();
  const MissionResult plain = RunMission(known, MissionParts());
  CHECK(plain.status == MissionStatus::kReachedGoal);
  CHECK(plain.replans.empty());
}

namespace {

int counted_plans = 0;  // calls of the test's planner

// A planner of the test's own: RRT* through the seam, counting its queries.
class CountingPlanner : public Planner {
 public:
  explicit CountingPlanner(std::unique_ptr<Planner> inner) : inner_(std::move(inner)) {}
  PlanResult Plan(const Vec3& start, const Vec3& goal) override {
    ++counted_plans;
    return inner_->Plan(start, goal);
  }

 private:
  std::unique_ptr<Planner> inner_;
};

}  // namespace

TEST_CASE("replanning goes through the planner seam: a planner registered by a test replans") {
  Planners().Register("counting", [](const PlannerConfig&, const PlannerContext& context) {
    // RRT* within replanning's counts (its own budget is RRT*'s, not this planner's)
    RrtStarParams counts;
    counts.max_iterations = ReplanParams().iterations;
    counts.max_search_iterations = ReplanParams().search_iterations;
    counts.time_budget = 10.0;
    const PlannerConfig rrt{"rrt_star", PluginParameters::Of(counts)};
    return std::unique_ptr<Planner>(std::make_unique<CountingPlanner>(MakePlanner(rrt, context)));
  });
  FlightSetup setup = RoomSetup(3);
  setup.planning.planner = "counting";
  counted_plans = 0;
  const MissionResult result = RunMission(setup, MissionParts());
  CAPTURE(ToString(result.flight.status));
  REQUIRE(result.status == MissionStatus::kReachedGoal);
  REQUIRE_FALSE(result.replans.empty());
  CHECK(result.replans.back().outcome.find("replanned") != std::string::npos);
  // the first plan, and the replan's queries: the test's planner made the new path
  CHECK(counted_plans >= 2);
}

namespace {

int counted_continues = 0;  // calls of the test's generator's Continue

// A trajectory generator of the test's own: min-snap through the seam, counting continuations.
class CountingGenerator : public TrajectoryGenerator {
 public:
  explicit CountingGenerator(std::unique_ptr<TrajectoryGenerator> inner)
      : inner_(std::move(inner)) {}
  TrajectoryResult Generate(const std::vector<Vec3>& path, const TrajectoryWorld& world) override {
    return inner_->Generate(path, world);
  }
  std::optional<TrajectoryResult> Continue(const StartState& start, const std::vector<Vec3>& path,
                                           const TrajectoryWorld& world) override {
    ++counted_continues;
    return inner_->Continue(start, path, world);
  }

 private:
  std::unique_ptr<TrajectoryGenerator> inner_;
};

}  // namespace

TEST_CASE("replanning goes through the generator seam: a generator registered by a test replans") {
  TrajectoryGenerators().Register("counting_continue", [](const GeneratorConfig& config) {
    GeneratorConfig minsnap = config;
    minsnap.method = "minsnap";
    return std::unique_ptr<TrajectoryGenerator>(
        std::make_unique<CountingGenerator>(MakeGenerator(minsnap)));
  });
  FlightSetup setup = RoomSetup(3);
  setup.planning.trajectory_method = "counting_continue";
  counted_continues = 0;
  const MissionResult result = RunMission(setup, MissionParts());
  CAPTURE(ToString(result.flight.status));
  REQUIRE(result.status == MissionStatus::kReachedGoal);
  REQUIRE_FALSE(result.replans.empty());
  CHECK(result.replans.back().outcome.find("replanned") != std::string::npos);
  // the replan's new trajectory came from the test's generator
  CHECK(counted_continues >= 1);
}

}  // namespace aerobox

namespace aerobox {
namespace {

FlightSetup DepthRoom(std::uint64_t seed) {
  FlightSetup setup = RoomSetup(seed);
  setup.sensing.kind = SensingParams::Kind::kDepth;
  setup.sensing.range = 5.0;
  setup.flight.face_travel = true;
  return setup;
}

}  // namespace

namespace {

// The occupancy map's size in each telemetry sample.
class MapSizes : public MissionObserver {
 public:
  void OnSample(const TelemetrySample& s) override { sizes.push_back(s.map); }
  std::vector<OccupancySize> sizes;
};

}  // namespace

TEST_CASE("depth: the wall is found by its face, mapped, flown around, the same seed repeats") {
  MapSizes map_sizes;
  MissionParts parts;
  parts.observers.push_back(&map_sizes);
  const MissionResult first = RunMission(DepthRoom(3), parts);
  for (const ReplanEvent& e : first.replans)
    MESSAGE(e.t << " s " << e.trigger << ": " << e.outcome << ", path " << e.path_length << " m");
  MESSAGE(std::string(ToString(first.flight.status)) << " at " << first.flight.time << " s");
  CAPTURE(ToString(first.flight.status));
  REQUIRE(first.status == MissionStatus::kReachedGoal);  // no contact on the way
  CHECK(first.revealed_boxes == 1);
  REQUIRE_FALSE(first.replans.empty());
  CHECK(first.replans.front().trigger == "wall");
  CHECK(first.revealed_distance[0] > 0.0);
  CHECK(first.revealed_distance[0] <= 5.0);
  REQUIRE(first.occupancy.has_value());
  CHECK(first.occupancy->grid->occupied_count() > 100);
  // telemetry follows the map as it grows, to its final size
  REQUIRE_FALSE(map_sizes.sizes.empty());
  CHECK(map_sizes.sizes.front().free < map_sizes.sizes.back().free);
  CHECK(map_sizes.sizes.back().occupied == first.occupancy->grid->occupied_count());
  CHECK(map_sizes.sizes.back().free == first.occupancy->grid->free_count());
  const MissionResult again = RunMission(DepthRoom(3), MissionParts());
  CHECK(again.revealed_at == first.revealed_at);
  CHECK(again.flight.time == first.flight.time);
  CHECK(again.occupancy->grid->occupied_count() == first.occupancy->grid->occupied_count());
}

TEST_CASE("depth: a box hidden behind another is not known until it is in the line of sight") {
  // a short wall across the way with a pillar right behind it: a field-of-view sensor reveals
  // both at once, through the wall; the depth camera sees the pillar only from beside the wall
  std::vector<double> pillar_seen;
  for (const SensingParams::Kind kind :
       {SensingParams::Kind::kCamera, SensingParams::Kind::kDepth}) {
    FlightSetup setup = DepthRoom(3);
    setup.sensing.kind = kind;
    setup.map.boxes.clear();
    setup.map.boxes.push_back({{Vec3(5, 0.5, 0), Vec3(5.3, 3.5, 3)}, Vec3(1, 0, 0), "wall", 1});
    setup.map.boxes.push_back({{Vec3(6.3, 1.7, 0), Vec3(6.7, 2.3, 3)}, Vec3(0, 0, 1), "pillar", 2});
    setup.unknown = {true, true};
    const MissionResult result = RunMission(setup, MissionParts());
    CAPTURE(ToString(result.flight.status));
    CHECK(result.status == MissionStatus::kReachedGoal);
    REQUIRE(result.revealed_at.size() == 2);
    MESSAGE("wall " << result.revealed_at[0] << " s, pillar " << result.revealed_at[1] << " s");
    CHECK(result.revealed_at[0] >= 0);
    CHECK(result.revealed_at[1] >= result.revealed_at[0]);
    pillar_seen.push_back(result.revealed_at[1]);
  }
  // the field of view sees the pillar through the wall as soon as it is in range, while the
  // vehicle is still in front of the wall (4 m away at the start); the depth camera only once
  // the vehicle has come round the wall's end
  CHECK(pillar_seen[0] < 1.0);
  CHECK(pillar_seen[1] > pillar_seen[0] + 1.0);
}
}  // namespace aerobox

namespace aerobox {
namespace {

// A 10 x 4 x 3 m room with a wall across it at x = 5 to 5.3, from y = 0 to `wall_end` [m],
// unknown.
Map WallRoom(double wall_end) {
  Map map;
  map.name = "wall room";
  map.bounds = {Vec3(0, 0, 0), Vec3(10, 4, 3)};
  map.boxes.push_back({{Vec3(5, 0, 0), Vec3(5.3, wall_end, 3)}, Vec3(1, 0, 0), "wall", 1});
  return map;
}

// From rest at `from` to rest at `to` [m] along the straight line between them in `duration`
// [s] (a cubic in time), at rest there after.
Reference FromRest(const Vec3& from, const Vec3& to, double duration) {
  Reference r;
  r.duration = duration;
  r.evaluate = [from, to, duration](double t, int derivative) -> Vec3 {
    const double s = std::min(t, duration) / duration;
    if (derivative == kPosition) return from + (to - from) * (3 * s * s - 2 * s * s * s);
    if (derivative == kVelocity) return (to - from) * (6 * s - 6 * s * s) / duration;
    return Vec3::Zero();
  };
  return r;
}

// The room's replanner (a 3 m omnidirectional sensor) for a flight from `from` to `to` [m].
Replanner WallRoomReplanner(const Map& map, const Vec3& from, const Vec3& to) {
  SensingParams sensing;
  sensing.range = 3.0;
  return Replanner(map, {true}, CollisionParams{}, CollisionParams{Vec3(0.1, 0.1, 0.05), 0.05},
                   PlannerConfig{}, GeneratorConfig{}, sensing, ReplanParams{}, {to}, {from, to},
                   1);
}

}  // namespace

TEST_CASE("a vehicle whose every stop ahead is blocked still brakes rather than fly on") {
  // a wall across the whole room, found 0.8 m ahead of a vehicle at 2 m/s: no path past it,
  // and no stop along the travel that keeps the trajectory's clearance from it
  const Vec3 from(1, 2, 1.5), to(9, 2, 1.5);
  Reference straight;
  straight.duration = 4.0;
  straight.evaluate = [from, to](double t, int derivative) -> Vec3 {
    if (derivative == kPosition) return from + (to - from) * (t / 4.0);
    if (derivative == kVelocity) return (to - from) / 4.0;
    return Vec3::Zero();
  };
  Replanner replanner = WallRoomReplanner(WallRoom(4.0), from, to);
  State state;
  state.p_W = straight.evaluate(1.6, kPosition);  // x = 4.2
  state.v_W = straight.evaluate(1.6, kVelocity);
  const std::optional<Reference> next = replanner.Update(1.6, 1.6, state, 0, straight);
  REQUIRE(replanner.events().size() == 1);
  CHECK(replanner.events()[0].outcome == "braking (no path)");
  REQUIRE(next.has_value());
  // the new reference comes to rest, not far beyond the braking distance
  CHECK(next->evaluate(next->duration, kVelocity).norm() < 1e-6);
  CHECK(next->evaluate(next->duration, kPosition).x() < 6.0);
  CHECK(next->evaluate(next->duration, kPosition).x() > 4.2);
}

TEST_CASE("a braked vehicle at rest does not repeat a search that found nothing") {
  // a wall across the whole room found 2 m ahead of a vehicle setting off: no path past it;
  // once the vehicle is at rest, another search would have the same start, world and seed
  Planners().Register("counting_at_rest", [](const PlannerConfig&, const PlannerContext& context) {
    const PlannerConfig rrt{"rrt_star", {}};
    return std::unique_ptr<Planner>(std::make_unique<CountingPlanner>(MakePlanner(rrt, context)));
  });
  const Vec3 from(3, 2, 1.5), to(9, 2, 1.5);
  const Reference ahead = FromRest(from, to, 4.0);  // from rest, straight through the wall
  SensingParams sensing;
  sensing.range = 3.0;
  Replanner replanner(WallRoom(4.0), {true}, CollisionParams{},
                      CollisionParams{Vec3(0.1, 0.1, 0.05), 0.05},
                      PlannerConfig{"counting_at_rest", {}}, GeneratorConfig{}, sensing,
                      ReplanParams{}, {to}, {from, to}, 1);
  State state;
  state.p_W = from;
  counted_plans = 0;
  const std::optional<Reference> brake = replanner.Update(0.0, 0.0, state, 0, ahead);
  REQUIRE(brake.has_value());
  REQUIRE(replanner.events().size() == 1);
  CHECK(replanner.events()[0].outcome == "braking (no path)");
  CHECK(counted_plans >= 1);
  // at rest at the brake's end: the first attempt searches, then none while nothing new is known
  state.p_W = brake->evaluate(brake->duration, kPosition);
  const auto attempt = [&](int i) {
    CHECK_FALSE(replanner.Update(0.04 * i, brake->duration + 0.04 * i, state, 0, *brake));
  };
  attempt(1);
  const int searched = counted_plans;
  for (int i = 2; i <= 10; ++i) attempt(i);
  CHECK(counted_plans == searched);
}

TEST_CASE("a vehicle at rest within the clearance of a box just found backs off and replans") {
  // a half wall found 2 cm from the body of a vehicle hovering before it: the trajectory's
  // clearance (0.05 m) no longer holds where it is, so no plan may start there
  const Vec3 from(4.93, 1, 1.5), to(9, 1, 1.5);
  const Reference ahead = FromRest(from, to, 4.0);  // from rest, straight through the wall
  Replanner replanner = WallRoomReplanner(WallRoom(2.5), from, to);
  State state;
  state.p_W = from;
  const std::optional<Reference> next = replanner.Update(0.0, 0.0, state, 0, ahead);
  REQUIRE(replanner.events().size() == 1);
  CHECK(replanner.events()[0].outcome == "replanned");
  REQUIRE(next.has_value());
  // it backs away from the wall first, then goes round its end
  CHECK(next->evaluate(0.5, kPosition).x() < from.x());
  bool round = false;
  for (double t = 0; t <= next->duration; t += 0.05)
    round |= next->evaluate(t, kPosition).y() > 2.5;
  CHECK(round);
  CHECK(next->evaluate(next->duration, kPosition).isApprox(to, 1e-3));
}

TEST_CASE("depth: the reference ends at rest before what the camera has not seen, and goes on") {
  // an empty 12 m room seen by a 5 m depth camera: the straight way to the goal 8 m ahead
  // leaves what the first frame saw about 5 m out
  Map room;
  room.name = "empty room";
  room.bounds = {Vec3(0, 0, 0), Vec3(12, 4, 3)};
  const Vec3 from(1, 2, 1.5), to(9, 2, 1.5);
  const Reference ahead = FromRest(from, to, 6.0);  // from rest, straight to the goal
  SensingParams sensing;
  sensing.kind = SensingParams::Kind::kDepth;
  sensing.range = 5.0;
  Replanner replanner(room, {}, CollisionParams{}, CollisionParams{Vec3(0.1, 0.1, 0.05), 0.05},
                      PlannerConfig{}, GeneratorConfig{}, sensing, ReplanParams{}, {to}, {from, to},
                      1);
  State state;
  state.p_W = from;
  const std::optional<Reference> first = replanner.Update(0.0, 0.0, state, 0, ahead);
  REQUIRE(first.has_value());
  REQUIRE(replanner.events().size() == 1);
  CHECK(replanner.events()[0].trigger == "seen further");
  // it stops short of the goal, at rest, and never passes a cell the camera has not seen
  const Vec3 end = first->evaluate(first->duration, kPosition);
  MESSAGE("the first reference ends at x = " << end.x() << " m");
  CHECK(first->evaluate(first->duration, kVelocity).norm() < 1e-6);
  CHECK(end.x() > 4.0);
  CHECK(end.x() < 6.0);
  int unseen = 0;
  for (double t = 0; t <= first->duration; t += 0.02) {
    const Vec3 p = first->evaluate(t, kPosition);
    unseen += (p - from).norm() > 0.3 && replanner.occupancy()->At(p) == Occupancy::kUnknown;
  }
  CHECK(unseen == 0);
  // nothing new seen from the same place: it keeps the reference
  CHECK_FALSE(replanner.Update(0.04, 0.04, state, 0, *first).has_value());
  // from the end, at rest, the camera sees the rest of the way: the reference goes on to the goal
  state.p_W = end;
  const std::optional<Reference> second =
      replanner.Update(first->duration, first->duration, state, 0, *first);
  REQUIRE(second.has_value());
  CHECK(replanner.events().back().trigger == "seen further");
  CHECK(second->evaluate(second->duration, kPosition).isApprox(to, 1e-3));
}

}  // namespace aerobox
