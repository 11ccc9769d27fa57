#include "scene/vehicle_mjcf.h"

#include <cmath>

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
constexpr int kGuardSegments = 12;      // capsules that make up one guard ring

const char* const kShellRgba = "0.93 0.93 0.91 1";
const char* const kDarkRgba = "0.15 0.15 0.17 1";
const char* const kPropRgba = "0.25 0.25 0.28 0.55";
const char* const kGuardRgba = "0.55 0.57 0.6 1";

}  // namespace

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

void WriteVehicleBody(const QuadParams& params, const Vec3& p_W, const Vec3& chase_offset_W,
                      XmlWriter* xml) {
  xml->Open("body", {{"name", model_names::kBody}, {"pos", Vec(p_W)}});
  xml->Leaf("freejoint", {{"name", "quad_root"}});
  xml->Leaf("inertial",
            {{"pos", "0 0 0"}, {"mass", Num(params.mass)}, {"diaginertia", Vec(params.inertia)}});
  xml->Leaf("camera", {{"name", model_names::kChaseCamera},
                       {"mode", "trackcom"},
                       {"pos", Vec(chase_offset_W)},
                       {"xyaxes", CameraXyAxes(chase_offset_W, Vec3::Zero())}});

  // collision: one box of the vehicle's full size, hidden in group 3
  xml->Leaf("geom", {{"name", model_names::kHullGeom},
                     {"type", "box"},
                     {"size", Vec(0.5 * params.collision_size)},
                     {"group", "3"},
                     {"rgba", "0.9 0.2 0.2 0.3"}});

  // visuals: shell, camera, arms, motors, propellers, guards
  xml->Leaf("geom", {{"name", "quad_shell"},
                     {"type", "box"},
                     {"class", "visual"},
                     {"size", Vec(Vec3(kShellHalfLength, kShellHalfWidth, kShellHalfHeight))},
                     {"rgba", kShellRgba}});
  xml->Leaf("geom", {{"name", "quad_camera"},
                     {"type", "sphere"},
                     {"class", "visual"},
                     {"size", Num(0.004)},
                     {"pos", Vec(Vec3(kShellHalfLength, 0, 0.002))},
                     {"rgba", kDarkRgba}});
  for (int i = 0; i < kNumRotors; ++i) {
    const std::string n = std::to_string(i);
    const Vec3 rotor = RotorPosition_B(params, i);
    Eigen::Matrix<double, 6, 1> arm;
    arm << Vec3::Zero(), rotor;
    xml->Leaf("geom", {{"name", "quad_arm_" + n},
                       {"type", "capsule"},
                       {"class", "visual"},
                       {"size", Num(kArmRadius)},
                       {"fromto", Vec(arm)},
                       {"rgba", kShellRgba}});
    xml->Leaf("geom", {{"name", "quad_motor_" + n},
                       {"type", "cylinder"},
                       {"class", "visual"},
                       {"size", Vec(Eigen::Vector2d(kMotorRadius, 0.5 * kRotorHeight))},
                       {"pos", Vec(Vec3(rotor + Vec3(0, 0, 0.5 * kRotorHeight - 0.004)))},
                       {"rgba", kDarkRgba}});
    xml->Leaf("geom", {{"name", "quad_prop_" + n},
                       {"type", "cylinder"},
                       {"class", "visual"},
                       {"size", Vec(Eigen::Vector2d(params.propeller_radius, 0.0006))},
                       {"pos", Vec(Vec3(rotor + Vec3(0, 0, kRotorHeight)))},
                       {"rgba", kPropRgba}});
    for (int s = 0; s < kGuardSegments; ++s) {
      const double a0 = 2.0 * M_PI * s / kGuardSegments;
      const double a1 = 2.0 * M_PI * (s + 1) / kGuardSegments;
      const Vec3 centre = rotor + Vec3(0, 0, kRotorHeight);
      Eigen::Matrix<double, 6, 1> segment;
      segment << centre + params.guard_radius * Vec3(std::cos(a0), std::sin(a0), 0),
          centre + params.guard_radius * Vec3(std::cos(a1), std::sin(a1), 0);
      xml->Leaf("geom", {{"name", "quad_guard_" + n + "_" + std::to_string(s)},
                         {"type", "capsule"},
                         {"class", "visual"},
                         {"size", Num(kGuardTube)},
                         {"fromto", Vec(segment)},
                         {"rgba", kGuardRgba}});
    }
  }

  // thrust acts at the rotor centres along the body z axis
  for (int i = 0; i < kNumRotors; ++i) {
    xml->Leaf("site", {{"name", model_names::RotorSite(i)},
                       {"pos", Vec(RotorPosition_B(params, i))},
                       {"size", Num(0.002)},
                       {"group", "4"}});
  }
  xml->Leaf("site", {{"name", model_names::kImuSite}, {"size", Num(0.002)}, {"group", "4"}});
  xml->Close();
}

void WriteVehicleActuators(const QuadParams& params, XmlWriter* xml) {
  for (int i = 0; i < kNumRotors; ++i) {
    Eigen::Matrix<double, 6, 1> gear;
    gear << 0, 0, 1, 0, 0, RotorYawMomentPerThrust(params, i);
    // filter dynamics: d(act)/dt = (ctrl - act) / tau, force = act (gain 1): first-order lag
    xml->Leaf("general", {{"name", model_names::ThrustActuator(i)},
                          {"site", model_names::RotorSite(i)},
                          {"gear", Vec(gear)},
                          {"dyntype", "filter"},
                          {"dynprm", Num(params.motor_time_constant)},
                          {"gaintype", "fixed"},
                          {"gainprm", "1"},
                          {"biastype", "none"},
                          {"ctrlrange", "0 " + Num(params.max_rotor_thrust)}});
  }
}

void WriteVehicleSensors(XmlWriter* xml) {
  xml->Leaf("accelerometer",
            {{"name", model_names::kAccelerometer}, {"site", model_names::kImuSite}});
  xml->Leaf("gyro", {{"name", model_names::kGyro}, {"site", model_names::kImuSite}});
}

}  // namespace aerobox::scene_detail
