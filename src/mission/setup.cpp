#include "mission/setup.h"

#include "scene/scene_mjcf.h"
#include "vehicle/quad_params.h"

namespace aerobox {

CollisionParams FlightSetup::PlannerCollision() const {
  return CollisionParams{vehicle.collision_size, planning.clearance};
}

CollisionParams FlightSetup::TrajectoryCollision() const {
  return CollisionParams{vehicle.collision_size, planning.trajectory_clearance};
}

void FlightSetup::Validate() const {
  vehicle.Validate();
  controller.Validate();
  flight.Validate();
  PlannerCollision().Validate();
  TrajectoryCollision().Validate();
  planning.rrt.Validate();
  planning.lattice.Validate();
  planning.trajectory.Validate();
}

std::string SceneMjcfFor(const FlightSetup& setup, const std::vector<bool>& keep_boxes) {
  const QuadParams& vehicle = setup.vehicle;
  SceneOptions options;
  options.keep_boxes = keep_boxes;
  options.vehicle_position = VehicleRestPosition(setup.map, vehicle, setup.start);
  options.heading_target = setup.goal;
  return BuildSceneMjcf(setup.map, vehicle, options);
}

}  // namespace aerobox
