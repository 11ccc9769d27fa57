#include "scene/scene_mjcf.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "scene/vehicle_mjcf.h"
#include "scene/xml_writer.h"
#include "vehicle/model_names.h"

namespace aerobox {
namespace {

using scene_detail::Num;
using scene_detail::Vec;
using scene_detail::XmlWriter;

constexpr double kFovyDeg = 45.0;       // vertical field of view of every camera [deg]
constexpr double kChaseDistance = 0.9;  // chase camera behind the vehicle [m]
constexpr double kChaseHeight = 0.45;   // and above it [m]
constexpr double kNearClip = 0.02;      // near clipping distance [m], for the chase camera

std::string Rgba(const Vec3& rgb, double alpha) {
  return Vec(Eigen::Vector4d(rgb.x(), rgb.y(), rgb.z(), alpha));
}

// Half the diagonal of the map bounds [m]: the radius the overview camera must fit.
double MapRadius(const Map& map) { return 0.5 * map.bounds.Size().norm(); }

void WriteHead(const Map& map, const SceneOptions& options,
               const std::vector<SceneVehicle>& vehicles, XmlWriter* xml) {
  const double radius = MapRadius(map);
  xml->Leaf("compiler",
            {{"angle", "radian"}, {"autolimits", "true"}, {"inertiafromgeom", "false"}});
  xml->Leaf("option",
            {{"timestep", Num(options.timestep)}, {"gravity", Vec(Vec3(0, 0, -kGravity))}});
  xml->Leaf("statistic", {{"center", Vec(map.bounds.Center())}, {"extent", Num(radius)}});
  xml->Open("visual");
  xml->Leaf("global", {{"offwidth", std::to_string(options.offscreen_width)},
                       {"offheight", std::to_string(options.offscreen_height)},
                       {"fovy", Num(kFovyDeg)}});
  xml->Leaf("quality", {{"shadowsize", "4096"}});
  // znear and zfar are fractions of the extent: a fixed near distance keeps the chase camera
  // usable in a city-sized map, and the far plane covers the overview camera's whole view
  xml->Leaf("map", {{"znear", Num(kNearClip / radius)}, {"zfar", "8"}});
  xml->Leaf(
      "headlight",
      {{"ambient", "0.35 0.35 0.35"}, {"diffuse", "0.45 0.45 0.45"}, {"specular", "0.1 0.1 0.1"}});
  xml->Close();

  xml->Open("default");
  xml->Open("default", {{"class", "visual"}});
  xml->Leaf("geom", {{"group", "2"}, {"contype", "0"}, {"conaffinity", "0"}});
  xml->Close();
  xml->Close();

  // the floor is tiled in 1 m squares, or 10 m squares in maps larger than 100 m
  const double tile = map.bounds.Size().head<2>().maxCoeff() > 100.0 ? 10.0 : 1.0;
  xml->Open("asset");
  xml->Leaf("texture", {{"name", "sky"},
                        {"type", "skybox"},
                        {"builtin", "gradient"},
                        {"rgb1", "0.62 0.76 0.92"},
                        {"rgb2", "0.96 0.97 1"},
                        {"width", "256"},
                        {"height", "256"}});
  xml->Leaf("texture", {{"name", "grid"},
                        {"type", "2d"},
                        {"builtin", "checker"},
                        {"rgb1", "0.84 0.85 0.86"},
                        {"rgb2", "0.78 0.79 0.8"},
                        {"mark", "edge"},
                        {"markrgb", "0.62 0.63 0.65"},
                        {"width", "512"},
                        {"height", "512"}});
  xml->Leaf("material", {{"name", "grid"},
                         {"texture", "grid"},
                         {"texuniform", "true"},
                         {"texrepeat", Vec(Eigen::Vector2d::Constant(1.0 / tile))},
                         {"reflectance", "0.05"}});
  for (const SceneVehicle& v : vehicles) scene_detail::WriteVehicleMeshes(v.params, v.name, xml);
  xml->Close();
}

void WriteBoundsEdges(const Map& map, XmlWriter* xml) {
  const Vec3 size = map.bounds.Size();
  const double thickness = std::max(0.003, 0.0004 * size.maxCoeff());  // half-thickness [m]
  int index = 0;
  // 12 edges: for each axis, the 4 edges parallel to it
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3;
    const int v = (axis + 2) % 3;
    for (int corner = 0; corner < 4; ++corner) {
      Vec3 centre = map.bounds.Center();
      centre[u] = (corner & 1) ? map.bounds.max[u] : map.bounds.min[u];
      centre[v] = (corner & 2) ? map.bounds.max[v] : map.bounds.min[v];
      Vec3 half = Vec3::Constant(thickness);
      half[axis] = 0.5 * size[axis];
      xml->Leaf("geom", {{"name", "bounds_edge_" + std::to_string(index++)},
                         {"class", "visual"},
                         {"type", "box"},
                         {"pos", Vec(centre)},
                         {"size", Vec(half)},
                         {"rgba", "0.2 0.45 0.8 0.6"}});
    }
  }
}

// A fixed camera that sees the whole map: it looks at the centre from the side across the
// longer horizontal axis (so the map spans the wide picture), from above, at the distance where
// the bounds' enclosing sphere fits the vertical field of view.
void WriteOverviewCamera(const Map& map, XmlWriter* xml) {
  const Vec3 size = map.bounds.Size();
  const Vec3 direction =
      (size.y() > size.x() ? Vec3(-1.0, -0.35, 0.85) : Vec3(-0.35, -1.0, 0.85)).normalized();
  const double distance = MapRadius(map) / std::sin(0.5 * kFovyDeg * M_PI / 180.0);
  const Vec3 target = map.bounds.Center();
  const Vec3 eye = target + distance * direction;
  xml->Leaf("camera", {{"name", model_names::kOverviewCamera},
                       {"pos", Vec(eye)},
                       {"xyaxes", scene_detail::CameraXyAxes(eye, target)}});
}

}  // namespace

void SceneOptions::Validate() const {
  if (!vehicle_position.allFinite()) {
    throw std::invalid_argument("SceneOptions.vehicle_position must be finite");
  }
  if (heading_target && !heading_target->allFinite()) {
    throw std::invalid_argument("SceneOptions.heading_target must be finite");
  }
  if (offscreen_width <= 0 || offscreen_height <= 0 || offscreen_width > 16384 ||
      offscreen_height > 16384) {
    throw std::invalid_argument("SceneOptions.offscreen size must lie in 1..16384 pixels, got " +
                                std::to_string(offscreen_width) + "x" +
                                std::to_string(offscreen_height));
  }
  if (!(std::isfinite(timestep) && timestep > 0.0)) {
    throw std::invalid_argument("SceneOptions.timestep must be positive, got " + Num(timestep));
  }
}

Vec3 VehicleRestPosition(const Map& map, const QuadParams& params, const Vec3& start) {
  Vec3 p = start;
  p.z() = std::max(p.z(), map.bounds.min.z() + 0.5 * params.collision_size.z());
  return p;
}

std::vector<bool> RouteBoxes(const Map& map, const std::vector<Vec3>& route, double margin) {
  // the route sampled at most half the margin apart; a box is kept when a sample lies within
  // the margin of it: every route point is within margin / 4 of a sample, so every box within
  // 3/4 of the margin of the route is kept for sure
  std::vector<Vec3> samples;
  const double spacing = std::max(0.5 * margin, 1e-3);
  for (size_t i = 0; i < route.size(); ++i) {
    if (i == 0) {
      samples.push_back(route[0]);
      continue;
    }
    const Vec3 step = route[i] - route[i - 1];
    const int pieces = std::max(1, static_cast<int>(std::ceil(step.norm() / spacing)));
    for (int k = 1; k <= pieces; ++k) samples.push_back(route[i - 1] + step * k / pieces);
  }
  std::vector<bool> keep(map.boxes.size(), false);
  for (size_t b = 0; b < map.boxes.size(); ++b) {
    const Aabb& box = map.boxes[b].extent;
    for (const Vec3& p : samples) {
      const Vec3 outside = (box.min - p).cwiseMax(p - box.max).cwiseMax(0.0);
      if (outside.norm() <= margin) {
        keep[b] = true;
        break;
      }
    }
  }
  return keep;
}

std::string SwarmRgba(int index) {
  static const char* const kPalette[] = {"0.90 0.30 0.25 1", "0.20 0.50 0.85 1", "0.25 0.70 0.35 1",
                                         "0.95 0.65 0.15 1", "0.60 0.35 0.75 1", "0.15 0.70 0.75 1",
                                         "0.85 0.40 0.65 1", "0.45 0.45 0.45 1"};
  if (index < 8) return kPalette[index];
  // then hues a golden angle apart, alternately lighter and darker: no two alike
  const double hue = std::fmod(0.13 + 0.618033988749895 * index, 1.0) * 6.0;
  const double value = index % 2 == 0 ? 0.9 : 0.6, chroma = 0.6 * value;
  const double x = chroma * (1.0 - std::abs(std::fmod(hue, 2.0) - 1.0));
  const int sector = static_cast<int>(hue) % 6;
  const double rgb[6][3] = {{chroma, x, 0}, {x, chroma, 0}, {0, chroma, x},
                            {0, x, chroma}, {x, 0, chroma}, {chroma, 0, x}};
  const double m = value - chroma;
  return Vec(Eigen::Vector4d(rgb[sector][0] + m, rgb[sector][1] + m, rgb[sector][2] + m, 1.0));
}

std::string BuildSceneMjcf(const Map& map, const std::vector<SceneVehicle>& vehicles,
                           const SceneOptions& options) {
  if (vehicles.empty()) throw std::invalid_argument("BuildSceneMjcf: no vehicle");
  for (const SceneVehicle& v : vehicles) {
    v.params.Validate();
    if (!v.position.allFinite()) {
      throw std::invalid_argument("SceneVehicle " + v.name + ": position must be finite");
    }
    if (v.name.find('/') != std::string::npos) {
      throw std::invalid_argument("SceneVehicle " + v.name + ": a name without '/'");
    }
  }
  options.Validate();
  XmlWriter xml;
  xml.Comment("generated by aerobox from map '" + map.name +
              "'; regenerate with 'aerobox scene' rather than editing");
  xml.Open("mujoco", {{"model", "aerobox " + map.name}});
  WriteHead(map, options, vehicles, &xml);

  xml.Open("worldbody");
  const Vec3 centre = map.bounds.Center();
  const Vec3 size = map.bounds.Size();
  xml.Leaf("light", {{"name", "sun"},
                     {"directional", "true"},
                     {"castshadow", "true"},
                     {"pos", Vec(Vec3(centre.x(), centre.y(), map.bounds.max.z() + size.norm()))},
                     {"dir", Vec(Vec3(0.3, 0.4, -1.0).normalized())},
                     {"diffuse", "0.6 0.6 0.6"},
                     {"specular", "0.2 0.2 0.2"}});
  // the floor plane: collides with the vehicle; its drawn size covers the bounds and a margin
  const Eigen::Vector2d floor_half =
      0.5 * size.head<2>() + Eigen::Vector2d::Constant(0.1 * size.head<2>().maxCoeff());
  xml.Leaf("geom", {{"name", model_names::kFloorGeom},
                    {"type", "plane"},
                    {"material", "grid"},
                    {"pos", Vec(Vec3(centre.x(), centre.y(), map.bounds.min.z()))},
                    {"size", Vec(Vec3(floor_half.x(), floor_half.y(), 1.0))}});
  WriteBoundsEdges(map, &xml);
  WriteOverviewCamera(map, &xml);
  if (!options.keep_boxes.empty() && options.keep_boxes.size() != map.boxes.size()) {
    throw std::invalid_argument("SceneOptions: keep_boxes needs one flag per map box");
  }
  for (size_t i = 0; i < map.boxes.size(); ++i) {
    if (!options.keep_boxes.empty() && !options.keep_boxes[i]) continue;
    const Box& box = map.boxes[i];
    xml.Leaf("geom", {{"name", box.name},
                      {"type", "box"},
                      {"pos", Vec(box.extent.Center())},
                      {"size", Vec(box.extent.HalfSize())},
                      {"rgba", Rgba(box.rgb, 1.0)}});
  }

  // the chase camera follows the first vehicle, behind it on the way to the heading target
  const Vec3& first = vehicles.front().position;
  Vec3 heading = Vec3::UnitX();
  if (options.heading_target) {
    const Vec3 towards = *options.heading_target - first;
    if (towards.head<2>().norm() > 1e-6) heading << towards.head<2>().normalized(), 0.0;
  }
  const Vec3 chase_offset = -kChaseDistance * heading + Vec3(0, 0, kChaseHeight);
  for (size_t i = 0; i < vehicles.size(); ++i) {
    const SceneVehicle& v = vehicles[i];
    scene_detail::WriteVehicleBody(v.params, v.name, v.position,
                                   i == 0 ? std::optional<Vec3>(chase_offset) : std::nullopt,
                                   v.shell_rgba, &xml);
  }
  xml.Close();  // worldbody

  xml.Open("actuator");
  for (const SceneVehicle& v : vehicles)
    scene_detail::WriteVehicleActuators(v.params, v.name, &xml);
  xml.Close();
  xml.Open("sensor");
  for (const SceneVehicle& v : vehicles) scene_detail::WriteVehicleSensors(v.name, &xml);
  xml.Close();
  xml.Close();  // mujoco
  return xml.Text();
}

std::string BuildSceneMjcf(const Map& map, const QuadParams& params, const SceneOptions& options) {
  return BuildSceneMjcf(map, {SceneVehicle{"", params, options.vehicle_position, ""}}, options);
}

std::string VehicleModelMjcf(const QuadParams& params) {
  Map volume;
  volume.name = "tello";
  volume.bounds = {Vec3(-1, -1, 0), Vec3(1, 1, 2)};
  SceneOptions options;
  options.vehicle_position = VehicleRestPosition(volume, params, Vec3::Zero());
  return BuildSceneMjcf(volume, params, options);
}

}  // namespace aerobox
