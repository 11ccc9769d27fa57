#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "perception/occupancy_grid.h"

using namespace aerobox;

namespace {

// A wall across the room at x 5..5.3, with the camera at x = 1 looking along +x.
struct Room {
  Aabb bounds{Vec3(0, 0, 0), Vec3(10, 6, 3)};
  std::vector<Aabb> boxes{{Vec3(5, 1, 0), Vec3(5.3, 5, 3)}};
  State body;
  DepthCameraParams params;
  Room() {
    body.p_W = Vec3(1, 3, 1.5);
    params.range = 8.0;
  }
  DepthImage Frame() { return DepthCamera(params, 1).Capture(body, boxes, bounds); }
};

}  // namespace

TEST_CASE(
    "occupancy: a wall seen from the front is occupied, the space before it free, behind it "
    "unknown") {
  Room room;
  OccupancyGrid grid(room.bounds, OccupancyParams());
  CHECK(grid.At(Vec3(3, 3, 1.5)) == Occupancy::kUnknown);
  const int added = grid.Insert(room.Frame(), room.params.range, {});
  CHECK(added > 100);
  CHECK(grid.At(Vec3(5.05, 3, 1.5)) == Occupancy::kOccupied);  // the wall's face
  CHECK(grid.At(Vec3(5.05, 2, 1.0)) == Occupancy::kOccupied);
  CHECK(grid.At(Vec3(3, 3, 1.5)) == Occupancy::kFree);  // between camera and wall
  CHECK(grid.At(Vec3(4.8, 3.1, 1.6)) == Occupancy::kFree);
  CHECK(grid.At(Vec3(5.2, 3, 1.5)) == Occupancy::kUnknown);  // inside the wall
  CHECK(grid.At(Vec3(7, 3, 1.5)) == Occupancy::kUnknown);    // behind it
  CHECK(grid.At(Vec3(1, 3, 2.9)) == Occupancy::kUnknown);    // out of the field of view
  // every occupied box is a cell-aligned slab of the wall's face, and together they cover the
  // occupied cells exactly
  double volume = 0.0;
  for (const Aabb& b : grid.OccupiedBoxes()) {
    CHECK(b.min.x() == doctest::Approx(5.0));
    CHECK(b.max.x() == doctest::Approx(5.1));
    volume += b.Size().prod();
  }
  CHECK(volume == doctest::Approx(grid.occupied_count() * 1e-3));
  CHECK(grid.OccupiedBoxes().size() < static_cast<size_t>(grid.occupied_count()) / 5);
  // the same frame again changes nothing's state; the wall stays occupied
  CHECK(grid.Insert(room.Frame(), room.params.range, {}) == 0);
  CHECK(grid.At(Vec3(5.05, 3, 1.5)) == Occupancy::kOccupied);
}

TEST_CASE("occupancy: a known box clears the space before it and is not added") {
  Room room;
  OccupancyGrid grid(room.bounds, OccupancyParams());
  CHECK(grid.Insert(room.Frame(), room.params.range, {true}) == 0);
  CHECK(grid.occupied_count() == 0);
  CHECK(grid.At(Vec3(3, 3, 1.5)) == Occupancy::kFree);
  CHECK(grid.At(Vec3(7, 3, 1.5)) == Occupancy::kUnknown);
}

TEST_CASE("occupancy: a box that moved away is cleared by the rays that now pass through it") {
  Room room;
  OccupancyGrid grid(room.bounds, OccupancyParams());
  grid.Insert(room.Frame(), room.params.range, {});
  REQUIRE(grid.At(Vec3(5.05, 3, 1.5)) == Occupancy::kOccupied);
  room.boxes.clear();
  for (int i = 0; i < 5; ++i) grid.Insert(room.Frame(), room.params.range, {});
  CHECK(grid.At(Vec3(5.05, 3, 1.5)) == Occupancy::kFree);
  CHECK(grid.occupied_count() == 0);
  CHECK(grid.OccupiedBoxes().empty());
}

TEST_CASE("occupancy: a resolution too fine for the bounds is refused naming the key") {
  OccupancyParams params;
  params.resolution = 0.001;
  CHECK_THROWS_WITH_AS(OccupancyGrid(Aabb{Vec3(0, 0, 0), Vec3(100, 100, 10)}, params),
                       doctest::Contains("sensing.resolution"), std::invalid_argument);
}

TEST_CASE(
    "occupancy: with columns, a wall seen in a band is taken whole up and down through unknown "
    "cells") {
  Room room;
  room.params.fov_vertical = 0.35;  // 20 deg: a band of the wall
  OccupancyGrid grid(room.bounds, OccupancyParams());
  grid.Insert(room.Frame(), room.params.range, {});
  REQUIRE(grid.occupied_count() > 0);
  double low = 3.0, high = 0.0, low_columns = 3.0, high_columns = 0.0;
  for (const Aabb& b : grid.OccupiedBoxes()) {
    low = std::min(low, b.min.z());
    high = std::max(high, b.max.z());
  }
  for (const Aabb& b : grid.OccupiedBoxes(true)) {
    low_columns = std::min(low_columns, b.min.z());
    high_columns = std::max(high_columns, b.max.z());
  }
  CHECK(low > 0.5);  // the band only
  CHECK(high < 2.5);
  CHECK(low_columns == doctest::Approx(0.0));  // down to the floor and up to the top
  CHECK(high_columns == doctest::Approx(3.0));
}

TEST_CASE("occupancy: a face seen along y merges into as few boxes as one seen along x") {
  // the room's wall turned: across y at y = 5, seen from y = 1 looking along +y
  Room room;
  room.bounds = {Vec3(0, 0, 0), Vec3(6, 10, 3)};
  room.boxes = {{Vec3(1, 5, 0), Vec3(5, 5.3, 3)}};
  room.body.p_W = Vec3(3, 1, 1.5);
  room.body.q_WB = Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()));
  OccupancyGrid turned(room.bounds, OccupancyParams());
  turned.Insert(room.Frame(), room.params.range, {});
  Room along_x;
  OccupancyGrid grid(along_x.bounds, OccupancyParams());
  grid.Insert(along_x.Frame(), along_x.params.range, {});
  REQUIRE(turned.occupied_count() > 100);
  CHECK(turned.OccupiedBoxes().size() < static_cast<size_t>(turned.occupied_count()) / 5);
  CHECK(turned.OccupiedBoxes().size() <= grid.OccupiedBoxes().size() + 2);
  double volume = 0.0;
  for (const Aabb& b : turned.OccupiedBoxes()) volume += b.Size().prod();
  CHECK(volume == doctest::Approx(turned.occupied_count() * 1e-3));
}

TEST_CASE(
    "occupancy: the merged boxes follow the map frame after frame, with and without columns") {
  // the camera walks past the wall and turns: after every frame the boxes cover exactly the
  // occupied cells (without columns), and with columns they cover at least them
  Room room;
  room.boxes.push_back({Vec3(3, 0.5, 0), Vec3(3.4, 0.9, 2)});  // a post before the wall
  OccupancyGrid grid(room.bounds, OccupancyParams());
  for (int frame = 0; frame < 8; ++frame) {
    room.body.p_W = Vec3(1 + 0.3 * frame, 1.5 + 0.4 * frame, 1.2 + 0.1 * frame);
    room.body.q_WB = Quat(Eigen::AngleAxisd(-0.3 + 0.1 * frame, Vec3::UnitZ()));
    grid.Insert(room.Frame(), room.params.range, {});
    double volume = 0.0;
    for (const Aabb& b : grid.OccupiedBoxes()) {
      volume += b.Size().prod();
      CHECK(grid.At(0.5 * (b.min + b.max)) == Occupancy::kOccupied);
    }
    CHECK(volume == doctest::Approx(grid.occupied_count() * 1e-3));
    double grown = 0.0;
    for (const Aabb& b : grid.OccupiedBoxes(true)) grown += b.Size().prod();
    CHECK(grown >= volume - 1e-9);
  }
  REQUIRE(grid.occupied_count() > 100);
}
