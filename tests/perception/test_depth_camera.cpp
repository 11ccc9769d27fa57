#include <doctest/doctest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <stdexcept>

#include "perception/depth_camera.h"
#include "scene/scene_mjcf.h"
#include "sim/simulation.h"
#include "vehicle/model_names.h"
#include "vehicle/quad_params.h"

using namespace aerobox;

namespace {

Map TwoBoxes() {
  Map map;
  map.name = "two_boxes";
  map.bounds = {Vec3(0, 0, 0), Vec3(10, 6, 4)};
  map.boxes.push_back({{Vec3(4, 1, 0), Vec3(5, 3, 3)}, Vec3(0.5, 0.5, 0.5), "near", 0});
  map.boxes.push_back({{Vec3(7, 0.5, 0), Vec3(8, 5.5, 4)}, Vec3(0.5, 0.5, 0.5), "far", 0});
  return map;
}

std::vector<Aabb> Extents(const Map& map) {
  std::vector<Aabb> boxes;
  for (const Box& b : map.boxes) boxes.push_back(b.extent);
  return boxes;
}

// 64 x 48 px, 10 m: small images of the two-box scenes
DepthCameraParams SmallCamera() {
  DepthCameraParams params;
  params.width = 64;
  params.height = 48;
  params.range = 10.0;
  return params;
}

State At(const Vec3& p, double yaw, double pitch = 0.0) {
  State s;
  s.p_W = p;
  s.q_WB = Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, Vec3::UnitY()));
  return s;
}

}  // namespace

TEST_CASE("depth camera: every pixel's depth is what MuJoCo's mj_ray sees, within 1 mm") {
  const Map map = TwoBoxes();
  const QuadParams vehicle;
  SceneOptions options;
  options.vehicle_position = Vec3(1, 3, 0.5);
  Simulation sim = Simulation::FromXml(BuildSceneMjcf(map, vehicle, options), "two boxes");
  const int body = mj_name2id(sim.model(), mjOBJ_BODY, model_names::kBody);
  const int floor_geom = mj_name2id(sim.model(), mjOBJ_GEOM, model_names::kFloorGeom);
  REQUIRE(body >= 0);
  DepthCameraParams params;
  params.width = 40;
  params.height = 30;
  params.range = 8.0;
  params.pitch = -0.2;
  DepthCamera camera(params, 1);
  int boxes = 0, floor = 0, nothing = 0;
  // the last pose stands beside the near box, which reaches behind the camera
  for (const State& s : {At(Vec3(1, 3, 1.5), 0.0), At(Vec3(2, 2, 2.5), 0.3, 0.2),
                         At(Vec3(6, 3, 1.0), 0.1, -0.1), At(Vec3(4.5, 3.4, 1.2), -0.6)}) {
    const DepthImage image = camera.Capture(s, Extents(map), map.bounds);
    for (int v = 0; v < image.height; ++v) {
      for (int u = 0; u < image.width; ++u) {
        const Vec3 ray_C = image.RayC(u, v);
        const Vec3 d = image.R_WC * ray_C;
        int geom = -1;
        // the boxes and the floor (group 0), not the drawn edges of the bounds (group 2)
        const mjtByte groups[mjNGROUP] = {1, 1, 0, 0, 0, 0};
        const double mj = mj_ray(sim.model(), sim.data(), image.origin_W.data(), d.data(), groups,
                                 1, body, &geom);
        const size_t k = static_cast<size_t>(v * image.width + u);
        // MuJoCo's floor is drawn 10 % wider than the bounds; the camera's floor is the bounds'
        const Vec3 at = image.origin_W + mj * d;
        const bool beyond =
            geom == floor_geom && (at.head<2>().array() < map.bounds.min.head<2>().array() ||
                                   at.head<2>().array() > map.bounds.max.head<2>().array())
                                      .any();
        if (mj < 0 || mj > params.range || beyond) {
          CHECK(image.depth[k] == 0.0f);
          ++nothing;
          continue;
        }
        REQUIRE(image.depth[k] > 0.0f);
        CHECK(std::abs(image.depth[k] / ray_C.z() - mj) < 1e-3);
        (image.hit[k] == kFloor ? floor : boxes) += 1;
      }
    }
  }
  CHECK(boxes > 500);
  CHECK(floor > 200);
  CHECK(nothing > 10);
}

TEST_CASE("depth camera: a box behind another is not seen, the point cloud lies on the surfaces") {
  const Map map = TwoBoxes();
  DepthCamera camera(SmallCamera(), 1);
  // on the near box's axis, low: the far box shows only above and beside the near one
  const DepthImage low = camera.Capture(At(Vec3(1, 2, 1.0), 0.0), Extents(map), map.bounds);
  int near = 0, far = 0;
  for (int v = 0; v < low.height; ++v) {
    for (int u = 0; u < low.width; ++u) {
      const size_t k = static_cast<size_t>(v * low.width + u);
      if (low.hit[k] == 0) {
        ++near;
        CHECK(std::abs(low.PointW(u, v).x() - 4.0) < 1e-4);  // its front face
      }
      if (low.hit[k] == 1) {
        ++far;
        const Vec3 p = low.PointW(u, v);
        CHECK(std::abs(p.x() - 7.0) < 1e-4);
        CHECK_FALSE((p.y() > 1 && p.y() < 3 && p.z() < 3));  // never behind the near box
      }
    }
  }
  CHECK(near > 100);
  CHECK(far > 0);
  // a small box entirely behind the near one is never hit
  std::vector<Aabb> hidden = Extents(map);
  hidden.push_back({Vec3(5.5, 1.8, 1.0), Vec3(5.8, 2.2, 1.4)});
  const DepthImage again = camera.Capture(At(Vec3(1, 2, 1.0), 0.0), hidden, map.bounds);
  for (const int hit : again.hit) CHECK(hit != 2);
}

TEST_CASE("depth camera: noise grows with the square of the depth, dropouts, the same seed") {
  Map map;
  map.bounds = {Vec3(0, -5, 0), Vec3(20, 5, 5)};
  DepthCameraParams params;
  params.width = 80;
  params.height = 60;
  params.range = 10.0;
  params.noise = 0.01;
  params.dropout = 0.2;
  const auto wall_at = [&](double x) {
    return std::vector<Aabb>{{Vec3(x, -5, 0), Vec3(x + 1, 5, 5)}};
  };
  for (const double x : {2.0, 4.0}) {
    DepthCamera camera(params, 7);
    const DepthImage image = camera.Capture(At(Vec3(0, 0, 2.5), 0.0), wall_at(x), map.bounds);
    double sum = 0.0, squares = 0.0;
    int returned = 0, dropped = 0;
    for (size_t k = 0; k < image.depth.size(); ++k) {
      if (image.hit[k] == kDropped) ++dropped;
      if (image.depth[k] <= 0.0f || image.hit[k] != 0) continue;
      const double exact = x - params.mount_B.x();  // the wall is flat and square to the view
      const double error = image.depth[k] - exact;
      sum += error;
      squares += error * error;
      ++returned;
    }
    const double sigma = std::sqrt(squares / returned);
    CHECK(std::abs(sum / returned) < 3 * sigma / std::sqrt(returned) + 1e-9);
    const double exact = x - params.mount_B.x();
    CHECK(sigma == doctest::Approx(0.01 * exact * exact).epsilon(0.1));
    CHECK(static_cast<double>(dropped) / image.depth.size() == doctest::Approx(0.2).epsilon(0.15));
    DepthCamera twin(params, 7);
    CHECK(twin.Capture(At(Vec3(0, 0, 2.5), 0.0), wall_at(x), map.bounds).depth == image.depth);
  }
}

TEST_CASE("depth camera: bad settings are refused naming the key") {
  DepthCameraParams params;
  params.fov_horizontal = 3.2;  // over 180 deg
  CHECK_THROWS_WITH_AS(params.Validate("sensing"), doctest::Contains("sensing.fov"),
                       std::invalid_argument);
  params = DepthCameraParams();
  params.width = 0;
  CHECK_THROWS_WITH_AS(params.Validate("sensing"), doctest::Contains("sensing.width"),
                       std::invalid_argument);
  params = DepthCameraParams();
  params.fov_vertical = 3.14159265358979;
  CHECK_THROWS_WITH_AS(params.Validate("sensing"), doctest::Contains("sensing.fov_vertical"),
                       std::invalid_argument);
  CHECK_NOTHROW(DepthCameraParams().Validate("sensing"));
}

TEST_CASE(
    "depth camera: of two faces at the same depth, the box first in the map is what a ray hit") {
  // the second box is nearer the camera, but on the faces they share at x = 4 the first wins,
  // as it would if the boxes were tried in the map's order
  Map map;
  map.bounds = {Vec3(0, 0, 0), Vec3(10, 6, 4)};
  map.boxes.push_back({{Vec3(4, 2.2, 0), Vec3(5, 4, 3)}, Vec3::Constant(0.5), "first", 0});
  map.boxes.push_back({{Vec3(4, 1.5, 0), Vec3(4.5, 3, 2)}, Vec3::Constant(0.5), "second", 0});
  DepthCamera camera(SmallCamera(), 1);
  const DepthImage image = camera.Capture(At(Vec3(1, 2, 1.0), 0.0), Extents(map), map.bounds);
  int shared = 0, second = 0;
  for (int v = 0; v < image.height; ++v) {
    for (int u = 0; u < image.width; ++u) {
      const int hit = image.hit[static_cast<size_t>(v * image.width + u)];
      if (hit < 0) continue;
      const Vec3 p = image.PointW(u, v);
      REQUIRE(std::abs(p.x() - 4.0) < 1e-4);
      const bool on_both = p.y() > 2.2 + 1e-3 && p.y() < 3 - 1e-3 && p.z() < 2 - 1e-3;
      const bool on_second = p.y() < 2.2 - 1e-3 && p.z() < 2 - 1e-3;
      if (on_both) {
        ++shared;
        CHECK(hit == 0);
      }
      if (on_second) {
        ++second;
        CHECK(hit == 1);
      }
    }
  }
  CHECK(shared > 20);
  CHECK(second > 20);
}
