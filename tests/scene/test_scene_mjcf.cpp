#include <doctest/doctest.h>

#include <fstream>
#include <iterator>
#include <stdexcept>

#include "scene/scene_mjcf.h"
#include "sim/mujoco_messages.h"
#include "sim/simulation.h"
#include "vehicle/model_names.h"

namespace aerobox {
namespace {

Map SmallMap() {
  Map map;
  map.name = "small";
  map.bounds = {Vec3(0, -1, 0), Vec3(4, 6, 3)};
  map.boxes.push_back({{Vec3(1, 1, 0), Vec3(2, 1.5, 3)}, Vec3(1, 0, 0), "block_0", 3});
  map.boxes.push_back({{Vec3(2.5, 3, 1), Vec3(3.5, 4, 2.5)}, Vec3(0, 0.5, 1), "block_1", 4});
  return map;
}

std::string Name(const mjModel* m, mjtObj type, int id) {
  const char* name = mj_id2name(m, type, id);
  return name != nullptr ? name : "";
}

}  // namespace

TEST_CASE("a generated scene loads in MuJoCo without warnings and matches the map") {
  const Map map = SmallMap();
  const QuadParams params;
  SceneOptions options;
  options.vehicle_position = Vec3(0.5, 0, 1);
  options.heading_target = Vec3(3, 5, 1);
  TakeMujocoWarnings();
  const Simulation sim = Simulation::FromXml(BuildSceneMjcf(map, params, options), "small");
  CHECK(TakeMujocoWarnings().empty());
  const mjModel* m = sim.model();

  // one box geom per map box, at its centre with its half-sizes and colour
  for (const Box& box : map.boxes) {
    CAPTURE(box.name);
    const int id = mj_name2id(m, mjOBJ_GEOM, box.name.c_str());
    REQUIRE(id >= 0);
    CHECK(m->geom_type[id] == mjGEOM_BOX);
    CHECK(m->geom_bodyid[id] == 0);
    for (int k = 0; k < 3; ++k) {
      CHECK(m->geom_pos[3 * id + k] == doctest::Approx(box.extent.Center()[k]).epsilon(1e-12));
      CHECK(m->geom_size[3 * id + k] == doctest::Approx(box.extent.HalfSize()[k]).epsilon(1e-12));
      CHECK(m->geom_rgba[4 * id + k] == doctest::Approx(box.rgb[k]).epsilon(1e-6));
    }
    CHECK(m->geom_contype[id] != 0);
  }

  // floor plane at the lower bound; bound edges are drawn but never collide
  const int floor = mj_name2id(m, mjOBJ_GEOM, model_names::kFloorGeom);
  REQUIRE(floor >= 0);
  CHECK(m->geom_type[floor] == mjGEOM_PLANE);
  CHECK(m->geom_pos[3 * floor + 2] == 0.0);
  int edges = 0;
  for (int g = 0; g < m->ngeom; ++g) {
    if (Name(m, mjOBJ_GEOM, g).rfind("bounds_edge_", 0) != 0) continue;
    ++edges;
    CHECK(m->geom_contype[g] == 0);
    CHECK(m->geom_conaffinity[g] == 0);
  }
  CHECK(edges == 12);

  // only the hull of the vehicle collides, with the box size of QuadParams
  const int body = mj_name2id(m, mjOBJ_BODY, model_names::kBody);
  int colliding = 0;
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_bodyid[g] != body || m->geom_contype[g] == 0) continue;
    ++colliding;
    CHECK(Name(m, mjOBJ_GEOM, g) == model_names::kHullGeom);
    for (int k = 0; k < 3; ++k) {
      CHECK(m->geom_size[3 * g + k] == doctest::Approx(0.5 * params.collision_size[k]));
    }
  }
  CHECK(colliding == 1);

  // the visuals are one mesh per colour, around the body's origin: MuJoCo computes every
  // geom's pose each step, so a few meshes rather than dozens of primitives keep a step cheap
  int visual = 0;
  const double reach = RotorPosition_B(params, 0).norm() + params.guard_radius + 0.005;  // [m]
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_bodyid[g] != body || m->geom_contype[g] != 0) continue;
    ++visual;
    CAPTURE(Name(m, mjOBJ_GEOM, g));
    CHECK(m->geom_type[g] == mjGEOM_MESH);
    // MuJoCo moves a mesh's vertices to its centroid and principal axes and offsets the geom
    // by as much; put them back in the body frame
    const Eigen::Map<const Eigen::Vector3d> pos(m->geom_pos + 3 * g);
    const Quat quat(m->geom_quat[4 * g], m->geom_quat[4 * g + 1], m->geom_quat[4 * g + 2],
                    m->geom_quat[4 * g + 3]);
    const int mesh = m->geom_dataid[g];
    double farthest = 0.0;
    for (int v = m->mesh_vertadr[mesh]; v < m->mesh_vertadr[mesh] + m->mesh_vertnum[mesh]; ++v) {
      const Vec3 local = Eigen::Map<const Eigen::Vector3f>(m->mesh_vert + 3 * v).cast<double>();
      const Vec3 p_B = pos + quat * local;
      farthest = std::max(farthest, p_B.head<2>().norm());
      CHECK(std::abs(p_B.z()) < 0.02);
    }
    CHECK(farthest < reach);
    CHECK(farthest > 0.02);
  }
  CHECK(visual == 4);

  // mass, inertia, actuators and time step come from QuadParams and SceneOptions
  CHECK(m->body_mass[body] == doctest::Approx(params.mass));
  for (int k = 0; k < 3; ++k)
    CHECK(m->body_inertia[3 * body + k] == doctest::Approx(params.inertia[k]));
  CHECK(m->opt.timestep == 0.001);
  CHECK(m->nu == kNumRotors);
  for (int i = 0; i < kNumRotors; ++i) {
    const int a = mj_name2id(m, mjOBJ_ACTUATOR, model_names::ThrustActuator(i).c_str());
    REQUIRE(a >= 0);
    CHECK(m->actuator_dyntype[a] == mjDYN_FILTER);
    CHECK(m->actuator_dynprm[a * mjNDYN] == doctest::Approx(params.motor_time_constant));
    CHECK(m->actuator_ctrllimited[a] == 1);
    CHECK(m->actuator_ctrlrange[2 * a + 1] == doctest::Approx(params.max_rotor_thrust));
    CHECK(m->actuator_gear[6 * a + 2] == 1.0);
    CHECK(m->actuator_gear[6 * a + 5] == doctest::Approx(RotorYawMomentPerThrust(params, i)));
    const int site = m->actuator_trnid[2 * a];
    for (int k = 0; k < 3; ++k) {
      CHECK(m->site_pos[3 * site + k] == doctest::Approx(RotorPosition_B(params, i)[k]));
    }
  }
  CHECK(m->nsensor == 2);
  CHECK(m->vis.global.offwidth == 1920);
  CHECK(m->vis.global.offheight == 1080);
  CHECK(mj_name2id(m, mjOBJ_CAMERA, model_names::kOverviewCamera) >= 0);
  CHECK(mj_name2id(m, mjOBJ_CAMERA, model_names::kChaseCamera) >= 0);
  CHECK(sim.VehicleState().p_W.isApprox(options.vehicle_position));
}

TEST_CASE("the overview camera sees every corner of the map") {
  const Map map = SmallMap();
  const Simulation sim = Simulation::FromXml(BuildSceneMjcf(map, QuadParams(), {}), "small");
  const mjModel* m = sim.model();
  const mjData* d = sim.data();
  const int cam = mj_name2id(m, mjOBJ_CAMERA, model_names::kOverviewCamera);
  const Vec3 eye(d->cam_xpos[3 * cam], d->cam_xpos[3 * cam + 1], d->cam_xpos[3 * cam + 2]);
  Mat3 r;  // columns: camera x (right), y (up), z (backwards) in the world
  for (int i = 0; i < 9; ++i) r(i / 3, i % 3) = d->cam_xmat[9 * cam + i];
  const double half_fovy = 0.5 * m->cam_fovy[cam] * M_PI / 180.0;
  const double aspect = 1920.0 / 1080.0;
  for (int corner = 0; corner < 8; ++corner) {
    Vec3 p;
    for (int k = 0; k < 3; ++k) p[k] = (corner >> k & 1) ? map.bounds.max[k] : map.bounds.min[k];
    const Vec3 c = r.transpose() * (p - eye);
    REQUIRE(c.z() < 0);  // in front of the camera
    CHECK(std::abs(c.y() / -c.z()) <= std::tan(half_fovy));
    CHECK(std::abs(c.x() / -c.z()) <= aspect * std::tan(half_fovy));
  }
}

TEST_CASE("scene text is deterministic and options are validated") {
  const Map map = SmallMap();
  SceneOptions options;
  options.vehicle_position = Vec3(0.5, 0.5, 0.5);
  CHECK(BuildSceneMjcf(map, QuadParams(), options) == BuildSceneMjcf(map, QuadParams(), options));
  options.offscreen_width = 0;
  CHECK_THROWS_AS(BuildSceneMjcf(map, QuadParams(), options), std::invalid_argument);
  options = SceneOptions();
  options.timestep = -1;
  CHECK_THROWS_AS(BuildSceneMjcf(map, QuadParams(), options), std::invalid_argument);
}

TEST_CASE("a start on the floor puts the vehicle resting on it") {
  const Map map = SmallMap();
  const QuadParams params;
  CHECK(VehicleRestPosition(map, params, Vec3(0.5, 0, 0)).z() ==
        doctest::Approx(0.5 * params.collision_size.z()));
  CHECK(VehicleRestPosition(map, params, Vec3(0.5, 0, 2)).z() == 2.0);
}

TEST_CASE("models/ holds the vehicle model generated from QuadParams") {
  const std::string generated = VehicleModelMjcf(QuadParams());
  std::ifstream in(std::string(AEROBOX_SOURCE_DIR) + "/models/tello.xml", std::ios::binary);
  REQUIRE_MESSAGE(in, "models/tello.xml is missing: run 'aerobox model -o models/tello.xml'");
  const std::string committed((std::istreambuf_iterator<char>(in)), {});
  CHECK_MESSAGE(committed == generated,
                "models/tello.xml is stale: run 'aerobox model -o models/tello.xml'");
  TakeMujocoWarnings();
  const Simulation sim = Simulation::FromXml(generated, "tello");
  CHECK(TakeMujocoWarnings().empty());
}

}  // namespace aerobox
