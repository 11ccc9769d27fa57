// The quadrotor's MJCF: body with visuals, collision box, rotor sites, IMU; thrust actuators with
// motor lag; IMU sensors. All numbers come from QuadParams. Internal to src/scene.
#pragma once

#include "scene/xml_writer.h"
#include "vehicle/quad_params.h"

namespace aerobox::scene_detail {

// Children of <asset>: the vehicle's visual meshes, one closed triangle mesh per colour, which
// the body's visual geoms reference.
void WriteVehicleMeshes(const QuadParams& params, XmlWriter* xml);

// <body name="quad"> at p_W with a free joint. `chase_offset_W` places the chase camera, which
// follows the vehicle's centre of mass at that world-frame offset [m] and looks at it.
void WriteVehicleBody(const QuadParams& params, const Vec3& p_W, const Vec3& chase_offset_W,
                      XmlWriter* xml);

// Children of <actuator>: one thrust actuator per rotor, thrust along the rotor site's z, the
// reaction moment through the gear's yaw entry, first-order lag as a filter, [0, max] thrust.
void WriteVehicleActuators(const QuadParams& params, XmlWriter* xml);

// Children of <sensor>: accelerometer and gyro at the IMU site.
void WriteVehicleSensors(XmlWriter* xml);

// xyaxes of a camera at `eye` looking at `target`, with world z up in the picture.
std::string CameraXyAxes(const Vec3& eye, const Vec3& target);

}  // namespace aerobox::scene_detail
