// The quadrotor's MJCF: body with visuals, collision box, rotor sites, IMU; thrust actuators with
// motor lag; IMU sensors. All numbers come from QuadParams. Internal to src/scene.
#pragma once

#include <optional>
#include <string>

#include "scene/xml_writer.h"
#include "vehicle/quad_params.h"

namespace aerobox::scene_detail {

// Every function names the vehicle's elements after `name` (model_names::Of): "" for the lone
// vehicle of a scene, whose elements keep their plain names.

// Children of <asset>: the vehicle's visual meshes, one closed triangle mesh per colour, which
// the body's visual geoms reference.
void WriteVehicleMeshes(const QuadParams& params, const std::string& name, XmlWriter* xml);

// <body name="quad"> at p_W with a free joint. `chase_offset_W`, when given, places the chase
// camera, which follows the vehicle's centre of mass at that world-frame offset [m] and looks at
// it. `shell_rgba` colours the shell ("": the Tello's white).
void WriteVehicleBody(const QuadParams& params, const std::string& name, const Vec3& p_W,
                      const std::optional<Vec3>& chase_offset_W, const std::string& shell_rgba,
                      XmlWriter* xml);

// Children of <actuator>: one thrust actuator per rotor, thrust along the rotor site's z, the
// reaction moment through the gear's yaw entry, first-order lag as a filter, [0, max] thrust.
void WriteVehicleActuators(const QuadParams& params, const std::string& name, XmlWriter* xml);

// Children of <sensor>: accelerometer and gyro at the IMU site.
void WriteVehicleSensors(const std::string& name, XmlWriter* xml);

// xyaxes of a camera at `eye` looking at `target`, with world z up in the picture.
std::string CameraXyAxes(const Vec3& eye, const Vec3& target);

}  // namespace aerobox::scene_detail
