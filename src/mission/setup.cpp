#include "mission/setup.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/number_format.h"
#include "scene/scene_mjcf.h"
#include "vehicle/quad_params.h"

namespace aerobox {

void PlanningSettings::DescribePlanner(Archive& a) {
  a.Number({"clearance", "m", "kept from obstacles and the bounds, beyond the vehicle's own box"},
           &clearance, 0, 10);
  rrt.Describe(a);
  a.Number({"lattice_spacing", "m", "the lattice's spacing, across and up"}, &lattice.spacing, 0.5,
           100);
  a.Boolean({"lattice_fallback", "", "a fine lattice searches the map when RRT* finds no path"},
            &lattice_fallback);
}

void PlanningSettings::DescribeTrajectory(Archive& a) {
  trajectory.Describe(a);
  a.Number({"clearance", "m", "kept from obstacles by the trajectory"}, &trajectory_clearance, 0,
           10);
}

CollisionParams FlightSetup::PlannerCollision() const {
  return CollisionParams{vehicle.collision_size, planning.clearance};
}

CollisionParams FlightSetup::TrajectoryCollision() const {
  return CollisionParams{vehicle.collision_size, planning.trajectory_clearance};
}

void FollowTheAir(bool feedforward_given, bool integral_given, FlightSetup* setup) {
  std::vector<ControllerConfig*> controllers = {&setup->controller};
  for (SwarmMember& m : setup->vehicles) controllers.push_back(&m.controller);
  for (ControllerConfig* c : controllers) {
    if (!feedforward_given) c->drag_feedforward = setup->aero.Enabled();
    if (!integral_given) {
      const bool integrates = setup->wind.Enabled() && !c->observer.enabled;
      c->se3.position_integral = integrates ? kSe3WindIntegral : Vec3::Zero();
    }
  }
}

FlightSetup FlightSetup::Member(size_t i) const {
  const SwarmMember& m = vehicles.at(i);
  FlightSetup one = *this;
  one.vehicles.clear();
  one.name = m.name;
  one.vehicle_kind = m.vehicle_kind;
  one.vehicle = m.vehicle;
  one.controller = m.controller;
  one.start = m.start;
  one.start_origin = "scenario";
  one.start_where = m.where;
  one.goal = m.goal;
  one.goal_origin = "scenario";
  one.goal_where = m.where;
  one.via = m.via;
  return one;
}

void FlightSetup::Validate() const {
  vehicle.Validate();
  controller.Validate();
  flight.Validate();
  wind.Validate();
  sensing.Validate();
  replan.Validate();
  PlannerCollision().Validate();
  TrajectoryCollision().Validate();
  planning.rrt.Validate();
  planning.lattice.Validate();
  planning.trajectory.Validate();
  if (HasUnknown()) {
    // the sensor reads at control steps
    const double per_period = controller.rate / sensing.rate;
    if (std::abs(per_period - std::round(per_period)) > 1e-6) {
      throw std::invalid_argument(
          "sensing.rate: " + FormatNumber(sensing.rate) + " Hz must divide the controller's rate " +
          FormatNumber(controller.rate) + " Hz (the sensor reads at control steps)");
    }
  }
  if (controller.kind == "indi" && sensors.imu.enabled && sensors.imu.rate < controller.rate) {
    // INDI differences the gyroscope at each control step: a reading held over several would
    // give zero, then a spike
    throw std::invalid_argument("sensors.imu.rate: " + FormatNumber(sensors.imu.rate) +
                                " Hz must be at least the controller's rate " +
                                FormatNumber(controller.rate) +
                                " Hz for indi, which differences the gyroscope at each step");
  }
  if (TrajectoryGenerators().Find(planning.trajectory_method) == nullptr) {
    throw std::invalid_argument("unknown trajectory generator '" + planning.trajectory_method +
                                "'");
  }
  if (planning.trajectory_method == "given" && planning.given_trajectory.size() < 2) {
    throw std::invalid_argument("trajectory method \"given\" needs a [trajectory] file");
  }
  swarm.Validate();
  for (size_t i = 0; i < vehicles.size(); ++i) {
    for (size_t j = 0; j < i; ++j) {
      if (vehicles[j].name == vehicles[i].name) {
        throw std::invalid_argument("vehicles: two are called \"" + vehicles[i].name + "\"");
      }
    }
    Member(i).Validate();
  }
}

std::string FlightSetup::ControllerMeasures() const {
  if (!MeasuresAcceleration(controller)) return "";
  return sensors.Enabled() ? "imu" : "ground truth (no IMU: sensors off)";
}

bool FlightSetup::HasUnknown() const {
  return std::find(unknown.begin(), unknown.end(), true) != unknown.end();
}

void AddAirAndSensors(const FlightSetup& setup, FlightLoop* loop) {
  loop->wind = setup.wind;
  loop->aero = setup.aero;
  loop->sensors = setup.sensors;
  loop->seed = setup.seed;
  loop->ground_z = setup.map.bounds.min.z();
}

std::string SceneMjcfFor(const FlightSetup& setup, const std::vector<bool>& keep_boxes) {
  const QuadParams& vehicle = setup.vehicle;
  SceneOptions options;
  options.keep_boxes = keep_boxes;
  if (!setup.vehicles.empty()) {
    // several vehicles: each at its start in its own colour, the chase camera on the first
    std::vector<SceneVehicle> vehicles;
    for (size_t i = 0; i < setup.vehicles.size(); ++i) {
      const SwarmMember& m = setup.vehicles[i];
      vehicles.push_back({m.name, m.vehicle, VehicleRestPosition(setup.map, m.vehicle, m.start),
                          SwarmRgba(static_cast<int>(i))});
    }
    options.heading_target = setup.vehicles.front().goal;
    return BuildSceneMjcf(setup.map, vehicles, options);
  }
  options.vehicle_position = VehicleRestPosition(setup.map, vehicle, setup.start);
  options.heading_target = setup.goal;
  return BuildSceneMjcf(setup.map, vehicle, options);
}

}  // namespace aerobox
