// The time-optimal point mass through waypoints: the reference `aerobox bench --sections speed`
// divides flight times by.
#include <doctest/doctest.h>

#include <stdexcept>

#include "trajectory/point_mass.h"
#include "trajectory/time_allocation.h"

namespace aerobox {
namespace {

PointMassParams Limits() {
  PointMassParams p;
  p.max_speed = 8.0;  // [m/s]
  p.max_accel = 5.0;  // [m/s^2]
  return p;
}

TEST_CASE("a straight segment takes the rest-to-rest trapezoid's time") {
  const PointMassParams p = Limits();
  for (const double length : {2.0, 30.0}) {  // a triangle, then a cruise
    const PointMassResult r = MinimumTimePointMass({Vec3(0, 0, 1), Vec3(length, 0, 1)}, p);
    REQUIRE(r.solved);
    const double trapezoid = TrapezoidTime(length, p.max_speed, p.max_accel);
    // constant acceleration per interval is a restriction of the continuous problem: never
    // faster than the bang-bang optimum, and close to it
    CHECK(r.time >= trapezoid * (1 - 1e-6));
    CHECK(r.time <= trapezoid * 1.02);
  }
}

TEST_CASE("a waypoint on the straight line costs nothing") {
  const PointMassParams p = Limits();
  const PointMassResult r = MinimumTimePointMass({Vec3(0, 0, 1), Vec3(7, 0, 1), Vec3(30, 0, 1)}, p);
  REQUIRE(r.solved);
  CHECK(r.time <= TrapezoidTime(30.0, p.max_speed, p.max_accel) * 1.02);
  CHECK(r.waypoint_velocity[1].x() > 7.0);  // it cruises through at nearly the limit
}

TEST_CASE("a corner costs less than stopping at it and more than a straight line") {
  const PointMassParams p = Limits();
  const PointMassResult r =
      MinimumTimePointMass({Vec3(0, 0, 1), Vec3(10, 0, 1), Vec3(10, 10, 1)}, p);
  REQUIRE(r.solved);
  const double stop = 2 * TrapezoidTime(10.0, p.max_speed, p.max_accel);
  const double straight = TrapezoidTime(20.0, p.max_speed, p.max_accel);
  CHECK(r.time < 0.95 * stop);
  CHECK(r.time > 1.05 * straight);
  const Vec3 corner = r.waypoint_velocity[1];
  CHECK(corner.norm() > 1.0);
  CHECK(corner.norm() <= p.max_speed + 1e-6);
  CHECK(corner.x() > 0);  // still moving along the first leg, already along the second
  CHECK(corner.y() > 0);
  CHECK(r.waypoint_velocity.front().norm() == doctest::Approx(0.0));
  CHECK(r.waypoint_velocity.back().norm() == doctest::Approx(0.0));
  REQUIRE(r.segment_times.size() == 2);
  CHECK(r.segment_times[0] + r.segment_times[1] == doctest::Approx(r.time));
}

TEST_CASE("bad point-mass input is refused") {
  CHECK_THROWS_AS(MinimumTimePointMass({Vec3(0, 0, 0)}), std::invalid_argument);
  CHECK_THROWS_AS(MinimumTimePointMass({Vec3(0, 0, 0), Vec3(0, 0, 0)}), std::invalid_argument);
  PointMassParams p;
  p.max_accel = 0.0;
  CHECK_THROWS_AS(MinimumTimePointMass({Vec3(0, 0, 0), Vec3(1, 0, 0)}, p), std::invalid_argument);
}

}  // namespace
}  // namespace aerobox
