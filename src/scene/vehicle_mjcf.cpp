#include "scene/vehicle_mjcf.h"

#include <cmath>
#include <string>
#include <vector>

#include "vehicle/model_names.h"

namespace aerobox::scene_detail {
namespace {

// Visual proportions of a Tello [m]; they do not affect the physics.
constexpr double kShellHalfLength = 0.026;
constexpr double kShellHalfWidth = 0.019;
constexpr double kShellHalfHeight = 0.011;
constexpr double kArmRadius = 0.0035;
constexpr double kMotorRadius = 0.0055;
constexpr double kRotorHeight = 0.013;  // propeller plane above the body origin
constexpr double kGuardTube = 0.0012;   // radius of the guard ring's tube
constexpr int kRoundSides = 12;         // facets around a cylinder, a ring or a tube

const char* const kShellRgba = "0.93 0.93 0.91 1";
const char* const kDarkRgba = "0.15 0.15 0.17 1";
const char* const kPropRgba = "0.25 0.25 0.28 0.55";
const char* const kGuardRgba = "0.55 0.57 0.6 1";

// The visual parts, one mesh and one geom each: shell (body and arms), dark (camera and motors),
// props, guards.
const char* const kVisualParts[] = {"shell", "dark", "props", "guards"};

const char* RgbaOf(const std::string& part) {
  if (part == "shell") return kShellRgba;
  if (part == "dark") return kDarkRgba;
  if (part == "props") return kPropRgba;
  return kGuardRgba;
}

// A closed triangle mesh with outward-facing (counter-clockwise) triangles [m, body frame].
struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<Eigen::Vector3i> faces;

  int Add(const Vec3& p) {
    vertices.push_back(p);
    return static_cast<int>(vertices.size()) - 1;
  }
};

// Unit vectors u, v with (u, v, axis) right-handed; u along `hint` projected off the axis.
void Basis(const Vec3& axis, const Vec3& hint, Vec3* u, Vec3* v) {
  Vec3 along = hint - hint.dot(axis) * axis;
  if (along.norm() < 1e-9) along = axis.unitOrthogonal();
  *u = along.normalized();
  *v = axis.cross(*u);
}

// A closed prism from a to b: `sides` corners at angles phase + 2 pi k / sides on an ellipse
// with radii (ru along u, rv along v). Few sides give flat faces (a box is 4 sides at phase
// pi/4); many give a smooth cylinder. Caps have their own vertices so they shade flat.
void AddPrism(const Vec3& a, const Vec3& b, double ru, double rv, int sides, double phase,
              const Vec3& hint, TriangleMesh* mesh) {
  const Vec3 axis = (b - a).normalized();
  Vec3 u, v;
  Basis(axis, hint, &u, &v);
  const auto corner = [&](int k) {
    const double angle = phase + 2.0 * M_PI * k / sides;
    return Vec3(ru * std::cos(angle) * u + rv * std::sin(angle) * v);
  };
  const bool smooth = sides >= 8;
  const int first = static_cast<int>(mesh->vertices.size());
  if (smooth) {  // shared side vertices: ring at a, then ring at b
    for (int k = 0; k < sides; ++k) mesh->Add(a + corner(k));
    for (int k = 0; k < sides; ++k) mesh->Add(b + corner(k));
    for (int k = 0; k < sides; ++k) {
      const int k1 = (k + 1) % sides;
      mesh->faces.emplace_back(first + k, first + k1, first + sides + k1);
      mesh->faces.emplace_back(first + k, first + sides + k1, first + sides + k);
    }
  } else {  // four vertices per side face
    for (int k = 0; k < sides; ++k) {
      const int q = mesh->Add(a + corner(k));
      mesh->Add(a + corner(k + 1));
      mesh->Add(b + corner(k + 1));
      mesh->Add(b + corner(k));
      mesh->faces.emplace_back(q, q + 1, q + 2);
      mesh->faces.emplace_back(q, q + 2, q + 3);
    }
  }
  const int centre_a = mesh->Add(a);
  const int centre_b = mesh->Add(b);
  const int cap = static_cast<int>(mesh->vertices.size());
  for (int k = 0; k < sides; ++k) mesh->Add(a + corner(k));
  for (int k = 0; k < sides; ++k) mesh->Add(b + corner(k));
  for (int k = 0; k < sides; ++k) {
    const int k1 = (k + 1) % sides;
    mesh->faces.emplace_back(centre_a, cap + k1, cap + k);
    mesh->faces.emplace_back(centre_b, cap + sides + k, cap + sides + k1);
  }
}

// A closed torus around `centre` in the body's xy plane: ring radius R, tube radius r.
void AddTorus(const Vec3& centre, double ring_radius, double tube_radius, TriangleMesh* mesh) {
  const int n = 2 * kRoundSides;  // around the ring
  const int m = 4;                // around the tube: a square section, turned 45 degrees
  const int first = static_cast<int>(mesh->vertices.size());
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n;
    const Vec3 out(std::cos(a), std::sin(a), 0.0);
    for (int j = 0; j < m; ++j) {
      const double b = 2.0 * M_PI * (j + 0.5) / m;
      mesh->Add(centre + (ring_radius + tube_radius * std::cos(b)) * out +
                tube_radius * std::sin(b) * Vec3::UnitZ());
    }
  }
  const auto at = [&](int i, int j) { return first + (i % n) * m + (j % m); };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      mesh->faces.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      mesh->faces.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
}

TriangleMesh VisualMesh(const QuadParams& params, const std::string& part) {
  TriangleMesh mesh;
  if (part == "shell") {
    AddPrism(Vec3(0, 0, -kShellHalfHeight), Vec3(0, 0, kShellHalfHeight),
             std::sqrt(2.0) * kShellHalfLength, std::sqrt(2.0) * kShellHalfWidth, 4, 0.25 * M_PI,
             Vec3::UnitX(), &mesh);
  }
  if (part == "dark") {  // the camera's lens, on the front face
    AddPrism(Vec3(kShellHalfLength - 0.001, 0, 0.002), Vec3(kShellHalfLength + 0.002, 0, 0.002),
             0.004, 0.004, kRoundSides, 0.0, Vec3::UnitZ(), &mesh);
  }
  for (int i = 0; i < kNumRotors; ++i) {
    const Vec3 rotor = RotorPosition_B(params, i);
    const Vec3 rotor_plane = rotor + Vec3(0, 0, kRotorHeight);
    if (part == "shell") {  // the arm: a flat bar from the shell to the motor
      AddPrism(Vec3(0.5 * rotor.x(), 0.5 * rotor.y(), 0), rotor, kArmRadius * std::sqrt(2.0),
               kArmRadius * std::sqrt(2.0), 4, 0.25 * M_PI, Vec3::UnitZ(), &mesh);
    }
    if (part == "dark") {
      AddPrism(rotor - Vec3(0, 0, 0.004), rotor + Vec3(0, 0, kRotorHeight - 0.004), kMotorRadius,
               kMotorRadius, kRoundSides, 0.0, Vec3::UnitX(), &mesh);
    }
    if (part == "props") {
      AddPrism(rotor_plane - Vec3(0, 0, 0.0006), rotor_plane + Vec3(0, 0, 0.0006),
               params.propeller_radius, params.propeller_radius, 2 * kRoundSides, 0.0,
               Vec3::UnitX(), &mesh);
    }
    if (part == "guards") AddTorus(rotor_plane, params.guard_radius, kGuardTube, &mesh);
  }
  return mesh;
}

}  // namespace

void WriteVehicleMeshes(const QuadParams& params, const std::string& name, XmlWriter* xml) {
  for (const char* part : kVisualParts) {
    const TriangleMesh mesh = VisualMesh(params, part);
    Eigen::VectorXd vertices(3 * mesh.vertices.size());
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
      // to the micrometre: exact enough to look right, and short in the scene's text
      vertices.segment<3>(3 * i) = (mesh.vertices[i] * 1e6).array().round() / 1e6;
    }
    std::string faces;
    for (const Eigen::Vector3i& f : mesh.faces) {
      faces += (faces.empty() ? "" : " ") + std::to_string(f[0]) + " " + std::to_string(f[1]) +
               " " + std::to_string(f[2]);
    }
    xml->Leaf("mesh", {{"name", model_names::Of(name, std::string("quad_") + part)},
                       {"vertex", Vec(vertices)},
                       {"face", faces}});
  }
}

std::string CameraXyAxes(const Vec3& eye, const Vec3& target) {
  const Vec3 forward = (target - eye).normalized();
  Vec3 right = forward.cross(Vec3::UnitZ());
  if (right.norm() < 1e-9) right = Vec3::UnitX();  // looking straight down or up
  right.normalize();
  const Vec3 up = right.cross(forward);
  Eigen::Matrix<double, 6, 1> axes;
  axes << right, up;
  return Vec(axes);
}

void WriteVehicleBody(const QuadParams& params, const std::string& name, const Vec3& p_W,
                      const std::optional<Vec3>& chase_offset_W, const std::string& shell_rgba,
                      XmlWriter* xml) {
  const auto of = [&name](const std::string& element) { return model_names::Of(name, element); };
  xml->Open("body", {{"name", of(model_names::kBody)}, {"pos", Vec(p_W)}});
  xml->Leaf("freejoint", {{"name", of("quad_root")}});
  xml->Leaf("inertial",
            {{"pos", "0 0 0"}, {"mass", Num(params.mass)}, {"diaginertia", Vec(params.inertia)}});
  if (chase_offset_W) {
    xml->Leaf("camera", {{"name", model_names::kChaseCamera},
                         {"mode", "trackcom"},
                         {"pos", Vec(*chase_offset_W)},
                         {"xyaxes", CameraXyAxes(*chase_offset_W, Vec3::Zero())}});
  }

  // collision: one box of the vehicle's full size, hidden in group 3
  xml->Leaf("geom", {{"name", of(model_names::kHullGeom)},
                     {"type", "box"},
                     {"size", Vec(0.5 * params.collision_size)},
                     {"group", "3"},
                     {"rgba", "0.9 0.2 0.2 0.3"}});

  // visuals: one mesh per colour (see WriteVehicleMeshes); a handful of geoms rather than one
  // per part keeps MuJoCo's per-step kinematics cheap
  for (const char* part : kVisualParts) {
    const std::string mesh = of(std::string("quad_") + part);
    const bool shell = std::string(part) == "shell" && !shell_rgba.empty();
    xml->Leaf("geom", {{"name", mesh},
                       {"type", "mesh"},
                       {"class", "visual"},
                       {"mesh", mesh},
                       {"rgba", shell ? shell_rgba : std::string(RgbaOf(part))}});
  }

  // thrust acts at the rotor centres along the body z axis
  for (int i = 0; i < kNumRotors; ++i) {
    xml->Leaf("site", {{"name", of(model_names::RotorSite(i))},
                       {"pos", Vec(RotorPosition_B(params, i))},
                       {"size", Num(0.002)},
                       {"group", "4"}});
  }
  xml->Leaf("site", {{"name", of(model_names::kImuSite)}, {"size", Num(0.002)}, {"group", "4"}});
  xml->Close();
}

void WriteVehicleActuators(const QuadParams& params, const std::string& name, XmlWriter* xml) {
  for (int i = 0; i < kNumRotors; ++i) {
    Eigen::Matrix<double, 6, 1> gear;
    gear << 0, 0, 1, 0, 0, RotorYawMomentPerThrust(params, i);
    // filter dynamics: d(act)/dt = (ctrl - act) / tau, force = act (gain 1): first-order lag
    xml->Leaf("general",
              {{"name", model_names::Of(name, model_names::ThrustActuator(i))},
               {"site", model_names::Of(name, model_names::RotorSite(i))},
               {"gear", Vec(gear)},
               {"dyntype", "filter"},
               {"dynprm", Num(params.motor_time_constant)},
               {"gaintype", "fixed"},
               {"gainprm", "1"},
               {"biastype", "none"},
               {"ctrlrange", Num(params.MinRotorThrust()) + " " + Num(params.MaxRotorThrust())}});
  }
}

void WriteVehicleSensors(const std::string& name, XmlWriter* xml) {
  const std::string site = model_names::Of(name, model_names::kImuSite);
  xml->Leaf("accelerometer",
            {{"name", model_names::Of(name, model_names::kAccelerometer)}, {"site", site}});
  xml->Leaf("gyro", {{"name", model_names::Of(name, model_names::kGyro)}, {"site", site}});
}

}  // namespace aerobox::scene_detail
