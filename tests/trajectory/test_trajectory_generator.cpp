#include <doctest/doctest.h>

#include "geometry/collision_world.h"
#include "trajectory/trajectory_generator.h"

namespace aerobox {
namespace {

TrajectoryWorld ViewOf(const CollisionWorld& world) {
  return {[&world](const Aabb& box) { return world.IsBoxFree(box); },
          [&world](const Vec3& a, const Vec3& b) { return world.IsSegmentFree(a, b); }};
}

// A corner around a block: a path that hugs it, as a shortcut planner returns it.
Map CornerMap() {
  Map map;
  map.bounds = {Vec3(0, 0, 0), Vec3(6, 6, 3)};
  map.boxes.push_back({{Vec3(1, 1, 0), Vec3(5, 5, 3)}, Vec3(1, 0, 0), "block", 1});
  return map;
}

const std::vector<Vec3> kPath = {Vec3(0.5, 5.5, 1.5), Vec3(0.5, 0.5, 1.5), Vec3(5.5, 0.5, 1.5)};

}  // namespace

TEST_CASE("corridors: grown until they touch, never blocked, holding their segment") {
  const CollisionWorld world(CornerMap(), CollisionParams());
  const auto box_free = [&world](const Aabb& box) { return world.IsBoxFree(box); };
  const std::optional<Aabb> corridor = GrowCorridor(kPath[0], kPath[1], box_free, 1.0);
  REQUIRE(corridor);
  CHECK(world.IsBoxFree(*corridor));
  CHECK(corridor->Contains(kPath[0]));
  CHECK(corridor->Contains(kPath[1]));
  // the x faces stop at the bounds (0.15) and at the grown block (1 - 0.15), to 1 mm
  CHECK(corridor->min.x() == doctest::Approx(0.15).epsilon(0.01));
  CHECK(corridor->max.x() == doctest::Approx(0.85).epsilon(0.01));
  // a diagonal past the block's corner has no free bounding box
  CHECK_FALSE(GrowCorridor(Vec3(0.5, 4, 1.5), Vec3(4, 0.5, 1.5), box_free, 1.0));
  const Aabb shrunk = ShrinkCorridor(*corridor, kPath[0], kPath[1], 0.01);
  CHECK(shrunk.IsInside(*corridor));
  CHECK(shrunk.Contains(kPath[0]));
}

TEST_CASE("a trajectory around a corner: free, inside its corridors, within its limits") {
  const Map map = CornerMap();
  const CollisionWorld world(map, CollisionParams());
  TrajectoryParams params;
  params.max_speed = 1.5;
  params.max_accel = 1.0;
  const TrajectoryResult result = GenerateTrajectory(kPath, ViewOf(world), params);
  REQUIRE(result.status == TrajectoryStatus::kSolved);
  const PiecewiseTrajectory& trajectory = result.trajectory;
  // dense samples, every 1 ms: limits (to the sampling of the scale: 0.5 %), corridors, free
  const std::vector<double> knots = trajectory.KnotTimes();
  for (double t = 0; t <= trajectory.duration(); t += 0.001) {
    CHECK(trajectory.Evaluate(t, kVelocity).norm() <= 1.5 * 1.005);
    CHECK(trajectory.Evaluate(t, kAcceleration).norm() <= 1.0 * 1.005);
    const Vec3 p = trajectory.Evaluate(t, kPosition);
    CHECK(world.IsPointFree(p));
    size_t segment = 0;
    while (segment + 2 < knots.size() && knots[segment + 1] < t) ++segment;
    if (result.corridors[segment]) CHECK(result.corridors[segment]->Inflated(1e-9).Contains(p));
  }
  CHECK(result.stats.max_speed <= 1.5 + 1e-9);
  CHECK(result.stats.duration == doctest::Approx(trajectory.duration()));
  CHECK(trajectory.Evaluate(trajectory.duration(), kPosition).isApprox(kPath.back()));
}

TEST_CASE("without corridors the corner is cut, and refinement inserts midpoints until free") {
  const CollisionWorld world(CornerMap(), CollisionParams());
  TrajectoryParams params;
  params.use_corridors = false;
  // a path that passes the block's corner 5 cm from its grown box: the unconstrained min-snap
  // curve cuts the corner into it
  const std::vector<Vec3> path = {Vec3(0.2, 5.8, 1.5), Vec3(0.8, 0.8, 1.5), Vec3(5.8, 0.2, 1.5)};
  REQUIRE(world.IsSegmentFree(path[0], path[1]));
  REQUIRE(world.IsSegmentFree(path[1], path[2]));
  params.max_refinements = 0;
  const TrajectoryResult first = GenerateTrajectory(path, ViewOf(world), params);
  CHECK(first.status == TrajectoryStatus::kCollides);
  params.max_refinements = 10;
  const TrajectoryResult refined = GenerateTrajectory(path, ViewOf(world), params);
  REQUIRE(refined.status == TrajectoryStatus::kSolved);
  CHECK(refined.stats.refinements >= 1);
  CHECK_FALSE(FirstCollisionTime(refined.trajectory, ViewOf(world), 0.001));
}

TEST_CASE("bad parameters are rejected with their name") {
  TrajectoryParams params;
  params.max_speed = 0;
  CHECK_THROWS_WITH_AS(params.Validate(), doctest::Contains("max_speed"), std::invalid_argument);
}

}  // namespace aerobox
