#include "mission/setup.h"

#include "scene/scene_mjcf.h"
#include "vehicle/quad_params.h"

namespace aerobox {

std::string SceneMjcfFor(const FlightSetup& setup, const std::vector<bool>& keep_boxes) {
  const QuadParams vehicle;
  SceneOptions options;
  options.keep_boxes = keep_boxes;
  options.vehicle_position = VehicleRestPosition(setup.map, vehicle, setup.start);
  options.heading_target = setup.goal;
  return BuildSceneMjcf(setup.map, vehicle, options);
}

}  // namespace aerobox
