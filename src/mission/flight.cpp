#include "mission/flight.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/fault_injection.h"
#include "common/number_format.h"
#include "scene/scene_mjcf.h"
#include "vehicle/model_names.h"

namespace aerobox {

void FlightParams::Validate() const {
  cascade.Validate();
  if (!(settle_time >= 0) || !(goal_tolerance > 0) || !(goal_speed > 0) ||
      !(flyaway_distance > 0)) {
    throw std::invalid_argument("FlightParams: times and tolerances must be positive");
  }
}

const char* ToString(FlightStatus status) {
  switch (status) {
    case FlightStatus::kReachedGoal:
      return "reached goal";
    case FlightStatus::kCollision:
      return "collision";
    case FlightStatus::kTimeout:
      return "timeout";
    case FlightStatus::kNonFinite:
      return "non-finite state";
    case FlightStatus::kFlyAway:
      return "fly-away";
  }
  return "?";
}

Reference ReferenceOf(const PiecewiseTrajectory& trajectory) {
  return {trajectory.duration(), [trajectory](double t, int derivative) -> Vec3 {
            return trajectory.Evaluate3(t, derivative);
          }};
}

void PlaceVehicleAtStart(const Map& map, const Vec3& requested, const Vec3& used, Simulation* sim) {
  const QuadParams vehicle;
  const Vec3 rest = VehicleRestPosition(map, vehicle, requested);
  if (rest.z() > map.bounds.min.z() + 0.5 * vehicle.collision_size.z() + 1e-9) {
    sim->SetVehicleState(State{used, Vec3::Zero(), Quat::Identity(), Vec3::Zero()});
    sim->SetRotorThrusts(Vec4::Constant(vehicle.HoverThrustPerRotor()));
  }
}

FlightResult FlyTrajectory(const Reference& reference, const FlightParams& params,
                           const QuadParams& vehicle,
                           const std::function<double(const Vec3&)>& clearance,
                           const std::function<void(const TelemetrySample&)>& telemetry,
                           Simulation* sim) {
  params.Validate();
  CascadeParams cascade_params = params.cascade;
  cascade_params.step = sim->timestep();
  CascadeController cascade(cascade_params, vehicle);
  FlightResult result;
  result.min_clearance = std::numeric_limits<double>::infinity();

  const double duration = reference.duration;
  const double end_time = duration + params.settle_time;
  const Vec3 goal = reference.evaluate(duration, kPosition);
  double yaw = 0.0;
  {
    const Vec3 x_W = sim->VehicleState().q_WB * Vec3::UnitX();
    yaw = std::atan2(x_W.y(), x_W.x());
  }
  // on the floor until the first step without floor contact
  bool airborne = sim->VehicleContacts().empty();
  double squared_error_sum = 0.0;
  long samples = 0;

  // an injected fault (common/fault_injection.h): the setpoint turns NaN from this time on
  double nan_from = std::numeric_limits<double>::infinity();
  if (const std::optional<std::string> at = InjectedFault("nonfinite")) {
    if (!ParseNumber(*at, &nan_from)) nan_from = 0.0;
  }

  const double t0 = sim->time();
  while (true) {
    const double t = sim->time() - t0;
    const State state = sim->VehicleState();
    if (!state.p_W.allFinite() || !state.v_W.allFinite() || !state.q_WB.coeffs().allFinite() ||
        !state.w_B.allFinite()) {
      result.status = FlightStatus::kNonFinite;
      break;
    }

    PositionSetpoint setpoint;
    setpoint.p_W = reference.evaluate(std::min(t, duration), kPosition);
    if (t < duration) {
      setpoint.v_W = reference.evaluate(t, kVelocity);
      setpoint.a_W = reference.evaluate(t, kAcceleration);
    }
    if (params.face_travel && setpoint.v_W.head<2>().norm() > 0.2) {
      yaw = std::atan2(setpoint.v_W.y(), setpoint.v_W.x());
    }
    setpoint.yaw = yaw;
    if (t >= nan_from) setpoint.p_W.x() = std::numeric_limits<double>::quiet_NaN();

    CascadeOutput control;
    if (!cascade.Update(setpoint, state, &control)) {
      result.status = FlightStatus::kNonFinite;
      break;
    }
    const double error = (state.p_W - setpoint.p_W).norm();
    if (control.outer_step) {
      squared_error_sum += error * error;
      ++samples;
      result.max_error = std::max(result.max_error, error);
      const double c = clearance ? clearance(state.p_W) : std::numeric_limits<double>::infinity();
      result.min_clearance = std::min(result.min_clearance, c);
      if (telemetry) {
        telemetry({t, state, setpoint, control, sim->RotorThrusts(), error, c});
      }
    }
    if (error > params.flyaway_distance) {
      result.status = FlightStatus::kFlyAway;
      break;
    }
    if (t >= duration && (state.p_W - goal).norm() < params.goal_tolerance &&
        state.v_W.norm() < params.goal_speed) {
      result.status = FlightStatus::kReachedGoal;
      break;
    }
    if (t >= end_time) {
      result.status = FlightStatus::kTimeout;
      break;
    }

    sim->Step(control.mixer.thrusts);
    ++result.steps;
    const std::vector<VehicleContact> contacts = sim->VehicleContacts();
    bool hit = false;
    for (const VehicleContact& contact : contacts) {
      if (!airborne && contact.other_geom == model_names::kFloorGeom) continue;
      result.obstacle = contact.other_geom;
      hit = true;
      break;
    }
    if (hit) {
      result.status = FlightStatus::kCollision;
      break;
    }
    if (contacts.empty()) airborne = true;
  }
  result.time = sim->time() - t0;
  result.rms_error = samples > 0 ? std::sqrt(squared_error_sum / samples) : 0.0;
  return result;
}

}  // namespace aerobox
