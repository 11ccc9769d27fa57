// Names of the vehicle's elements in every generated MJCF model: the contract between the scene
// writer (src/scene) and the simulation (src/sim).
#pragma once

#include <string>

namespace aerobox::model_names {

inline constexpr const char* kBody = "quad";           // the free-floating vehicle body
inline constexpr const char* kHullGeom = "quad_hull";  // its collision box
inline constexpr const char* kImuSite = "imu";
inline constexpr const char* kAccelerometer = "imu_accel";
inline constexpr const char* kGyro = "imu_gyro";
inline constexpr const char* kFloorGeom = "floor";
inline constexpr const char* kOverviewCamera = "overview";
inline constexpr const char* kChaseCamera = "chase";

// "rotor_0" .. "rotor_3" (sites) and "thrust_0" .. "thrust_3" (actuators), by the index of
// QuadParams::rotor_positions_B: rotor_0 is RotorPy's r1 (front-left) for the built-ins.
inline std::string RotorSite(int rotor) { return "rotor_" + std::to_string(rotor); }
inline std::string ThrustActuator(int rotor) { return "thrust_" + std::to_string(rotor); }

// An element of the vehicle called `vehicle` in a world of several ("cf1/quad", "cf1/thrust_0");
// the lone vehicle of a scene has no name, and its elements keep their plain names.
inline std::string Of(const std::string& vehicle, const std::string& element) {
  return vehicle.empty() ? element : vehicle + "/" + element;
}

}  // namespace aerobox::model_names
