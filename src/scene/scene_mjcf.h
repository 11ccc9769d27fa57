// Map + vehicle -> a self-contained MJCF scene (no includes, no files it depends on), so a
// written scene.xml loads from wherever it is, in aerobox or in MuJoCo's own tools.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "map/map.h"
#include "vehicle/quad_params.h"

namespace aerobox {

struct SceneOptions {
  // Where the vehicle's centre starts [m, world]. Use VehicleRestPosition() to turn a map's or a
  // scenario's start into this.
  Vec3 vehicle_position = Vec3::Zero();
  // Where the flight heads [m, world], when known: the chase camera sits behind the line from
  // the start towards it. Without it, the chase camera looks along +x.
  std::optional<Vec3> heading_target;
  // Off-screen render buffer [pixels]; renders larger than this are impossible.
  int offscreen_width = 1920;
  int offscreen_height = 1080;
  // Physics time step [s].
  double timestep = 0.001;
  // When not empty, one flag per map box: false leaves the box out of the scene, so MuJoCo
  // neither simulates nor draws it. MuJoCo 2.2 tests the vehicle against every geom of the world
  // body at each step; a city flight keeps only the buildings near its route (RouteBoxes).
  std::vector<bool> keep_boxes;

  // Throws std::invalid_argument for non-finite positions, non-positive sizes or time step.
  void Validate() const;
};

// The flags for SceneOptions::keep_boxes: true for the boxes within `margin` [m] of the route
// (a polyline through the points), false for the rest.
std::vector<bool> RouteBoxes(const Map& map, const std::vector<Vec3>& route, double margin);

// The vehicle's starting centre for a requested start point [m]: the point itself, raised so
// that the collision box's bottom is not below the floor (the map's lower z bound). A start on
// the floor, like RBE595 P2b's z = 0, puts the vehicle resting on the floor.
Vec3 VehicleRestPosition(const Map& map, const QuadParams& params, const Vec3& start);

// The scene: one named box geom per map box (its colour), a floor plane at the lower z bound,
// the bounds drawn as thin edges that never collide, a sun light, an "overview" camera that
// frames the whole map, a "chase" camera that follows the vehicle, and the vehicle with its
// actuators and sensors. Deterministic: the same input gives the same text.
std::string BuildSceneMjcf(const Map& map, const QuadParams& params, const SceneOptions& options);

// One vehicle of a scene with several.
struct SceneVehicle {
  std::string name;  // its elements are called "<name>/..." (model_names::Of); no '/' in it
  QuadParams params;
  Vec3 position = Vec3::Zero();  // its centre at the start [m] (VehicleRestPosition)
  std::string shell_rgba;        // "r g b a" of its shell ("": the Tello's white)
};

// The colour of the i-th vehicle of a swarm ("r g b a"), as the scene and the report draw it:
// eight well-separated colours, then hues a golden angle apart.
std::string SwarmRgba(int index);

// The scene with several vehicles in one world: as above, every vehicle with its own names,
// colour, actuators and sensors; the chase camera follows the first (SceneOptions'
// vehicle_position is not used: each vehicle brings its own).
std::string BuildSceneMjcf(const Map& map, const std::vector<SceneVehicle>& vehicles,
                           const SceneOptions& options);

// The vehicle alone, resting on a floor in a 2 m test volume: the models/ file.
std::string VehicleModelMjcf(const QuadParams& params);

}  // namespace aerobox
