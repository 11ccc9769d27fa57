#include "outputs/summary.h"

#include <mujoco/mujoco.h>

#include <cmath>

#include "common/number_format.h"
#include "planning/path_simplify.h"

namespace aerobox {
namespace {

void AddPoint(JsonObject* json, const std::string& key, const Vec3& p) {
  json->Add(key, std::vector<double>{p.x(), p.y(), p.z()});
}

// The speed the trajectory kept below [m/s]: the cap, or with min-time the vehicle's top speed
// when that is lower.
double SpeedLimit(const FlightSetup& setup) {
  const TrajectoryParams params = TrajectoryParamsFor(setup);
  return params.objective == TimeObjective::kMinTime ? EffectiveLimits(params).max_speed
                                                     : params.max_speed;
}

}  // namespace

std::string TrackingNote(const FlightSetup& setup, const FlightResult& flight) {
  if (flight.max_error <= kLargeTrackingError) return "";
  const TrajectoryParams& params = setup.planning.trajectory;
  if (params.objective == TimeObjective::kMinTime) {
    return "the vehicle was up to " + FormatNumber(std::round(flight.max_error * 100) / 100) +
           " m off its trajectory: the trajectory's margins (thrust_margin " +
           FormatNumber(params.thrust_margin) + ", max_tilt " + FormatNumber(params.max_tilt) +
           " rad) leave the controller too little";
  }
  return "the vehicle was up to " + FormatNumber(std::round(flight.max_error * 100) / 100) +
         " m off its trajectory: the limits (" + FormatNumber(setup.planning.trajectory.max_speed) +
         " m/s, " + FormatNumber(setup.planning.trajectory.max_accel) +
         " m/s^2) ask more than it can follow";
}

namespace {

// Obstacles found in flight: how many, every replan, when and how far away each box was first
// seen, and the depth camera's occupancy map.
void AddDiscovery(const FlightSetup& setup, const MissionResult& result, JsonObject* summary) {
  summary->Add("unknown_boxes", result.unknown_boxes).Add("revealed_boxes", result.revealed_boxes);
  std::vector<JsonObject> replans;
  for (const ReplanEvent& e : result.replans) {
    JsonObject r;
    r.Add("t_s", e.t)
        .Add("trigger", e.trigger)
        .Add("outcome", e.outcome)
        .Add("planning_time_s", e.planning_time)
        .Add("solve_time_s", e.solve_time)
        .Add("latency_s", e.latency)
        .Add("path_length_m", e.path_length)
        .Add("time_capped", e.time_capped);
    replans.push_back(r);
  }
  summary->Add("replans", replans);
  std::vector<JsonObject> revealed;
  for (size_t i = 0; i < result.revealed_at.size() && i < setup.map.boxes.size(); ++i) {
    if (result.revealed_at[i] < 0) continue;
    JsonObject r;
    r.Add("box", setup.map.boxes[i].name).Add("t_s", result.revealed_at[i]);
    if (i < result.revealed_distance.size()) r.Add("distance_m", result.revealed_distance[i]);
    revealed.push_back(r);
  }
  summary->Add("revealed", revealed);
  if (!result.occupancy) return;
  const OccupancyGrid& grid = *result.occupancy->grid;
  const SensingCost& cost = result.occupancy->cost;
  JsonObject map;
  map.Add("resolution_m", grid.resolution())
      .Add("cells", static_cast<long long>(grid.cell_count()))
      .Add("occupied_cells", static_cast<long long>(grid.occupied_count()))
      .Add("free_cells", static_cast<long long>(grid.free_count()))
      .Add("depth_frames", cost.frames)
      .Add("ray_cast_s", cost.capture)
      .Add("fusion_s", cost.fusion)
      .Add("planner_world_s", cost.rebuild);
  summary->Add("occupancy", map);
}

}  // namespace

void AddFlightNumbers(const FlightResult& flight, JsonObject* summary) {
  summary->Add("distance_flown_m", flight.distance)
      .Add("average_speed_mps", flight.AverageSpeed())
      .Add("top_speed_mps", flight.top_speed)
      .Add("peak_rotor_command_fraction", flight.peak_rotor_fraction)
      .Add("rotor_saturated_s", flight.saturated_time)
      .Add("tracking_rms_m", flight.rms_error)
      .Add("tracking_max_m", flight.max_error)
      .Add("takeoff_s", flight.takeoff_time)
      .Add("min_clearance_m", flight.min_clearance)
      .Add("collisions", flight.status == FlightStatus::kCollision ? 1 : 0)
      .Add("collision_with", flight.obstacle)
      .Add("simulation_warning", flight.message)
      .Add("control_rate_hz", flight.control_rate);
}

namespace {

// Where the run started and ended, how the path was planned, and what blocks a given path.
void AddPlan(const PlanOutcome& plan, JsonObject* summary) {
  AddPoint(summary, "start_requested", plan.start.requested);
  AddPoint(summary, "start", plan.start.used);
  AddPoint(summary, "goal_requested", plan.goal.requested);
  AddPoint(summary, "goal", plan.goal.used);
  summary->Add("planning_time_s", plan.result.stats.planning_time)
      .Add("planner_iterations", static_cast<long long>(plan.result.stats.iterations))
      .Add("planning_time_capped", plan.result.stats.time_capped);
  if (plan.result.status == PlanStatus::kPathBlocked) {
    // where a given path is blocked, and by what (a sweep or a script reads it)
    const PlanStats& stats = plan.result.stats;
    summary->Add("blocked_leg", stats.blocked_leg)
        .Add("blocked_point",
             std::vector<double>(stats.blocked_point.data(), stats.blocked_point.data() + 3))
        .Add("blocked_by", plan.blocked_by)
        .Add("blocked", DescribeBlockedPath(plan));
  }
}

// The trajectory along the path: its length, duration, limits and how it was solved.
void AddTrajectory(const FlightSetup& setup, const TrajectoryResult& trajectory,
                   const PlanOutcome& plan, JsonObject* summary) {
  summary->Add("path_length_m", PathLength(plan.result.path))
      .Add("trajectory_time_s", trajectory.stats.solve_time)
      .Add("trajectory_duration_s", trajectory.stats.duration)
      .Add("trajectory_max_speed_mps", trajectory.stats.max_speed)
      .Add("trajectory_max_accel_mps2", trajectory.stats.max_accel)
      .Add("speed_limit_mps", SpeedLimit(setup))
      .Add("accel_limit_mps2", TrajectoryParamsFor(setup).max_accel)
      .Add("trajectory_objective", ToString(setup.planning.trajectory.objective))
      // Ipopt's word, and whether the closed form was flown after Ipopt failed (a sweep counts
      // these)
      .Add("trajectory_solver_message", trajectory.stats.solver_message)
      .Add("trajectory_fallback", trajectory.stats.closed_form_fallback);
  if (setup.planning.trajectory.objective == TimeObjective::kMinTime) {
    // the limit the trajectory meets most closely (1: exactly at it)
    summary->Add("trajectory_binding_limit", trajectory.stats.binding_limit.limit)
        .Add("trajectory_binding_ratio", trajectory.stats.binding_limit.ratio)
        .Add("trajectory_binding_time_s", trajectory.stats.binding_limit.t);
  }
}

// The flight: its status, its numbers, the estimate, the wind met, a mission's goals.
void AddFlight(const FlightSetup& setup, const MissionResult& result, const OutputCounts& counts,
               JsonObject* summary) {
  const PlanOutcome& plan = result.plan;
  const FlightResult& flight = result.flight;
  summary->Add("tracking_warning", TrackingNote(setup, flight));
  summary->Add("flight_status", ToString(flight.status))
      .Add("flight_time_s", flight.time)
      .Add("flight_wall_time_s", result.flight_wall_time);
  AddFlightNumbers(flight, summary);
  summary->Add("telemetry_rate_hz", flight.control_rate / counts.telemetry_every)
      .Add("video_frames", counts.video_frames)
      .Add("video_fps", counts.video_fps);
  if (setup.sensors.Enabled()) {
    summary->Add("estimate_rms_m", flight.estimate_rms_error)
        .Add("estimate_max_m", flight.estimate_max_error);
  }
  if (setup.wind.Enabled()) summary->Add("max_wind_mps", flight.max_wind);
  if (!plan.via.empty()) {
    // a mission: every goal, whether and when it was reached
    std::vector<JsonObject> goals;
    for (size_t i = 0; i <= plan.via.size(); ++i) {
      const bool last = i == plan.via.size();
      const Vec3& p = last ? plan.goal.used : plan.via[i].used;
      const bool reached =
          last ? flight.status == FlightStatus::kReachedGoal : i < flight.goal_times.size();
      JsonObject goal;
      AddPoint(&goal, "goal", p);
      goal.Add("reached", reached)
          .Add("time_s", reached ? (last ? flight.time : flight.goal_times[i]) : -1.0);
      goals.push_back(goal);
    }
    summary->Add("goals", goals).Add("stop_at_goals", setup.stop_at_goals);
  }
}

// The world it flew in: what was on; and the versions.
void AddWorld(const FlightSetup& setup, JsonObject* summary) {
  JsonObject wind;
  AddPoint(&wind, "mean_mps", setup.wind.mean);
  wind.Add("turbulence", setup.wind.turbulence == Turbulence::kDryden ? "dryden" : "none")
      .Add("intensity_mps", std::vector<double>{setup.wind.intensity.x(), setup.wind.intensity.y(),
                                                setup.wind.intensity.z()})
      .Add("gusts", static_cast<int>(setup.wind.gusts.size()));
  summary->Add("wind", wind);
  JsonObject aero;
  aero.Add("body_drag", setup.aero.body_drag).Add("rotor_drag", setup.aero.rotor_drag);
  summary->Add("aero", aero);
  JsonObject sensors;
  sensors.Add("imu", setup.sensors.imu.enabled)
      .Add("position", !setup.sensors.position.enabled                           ? "none"
                       : setup.sensors.position.kind == PositionSensorKind::kGps ? "gps"
                                                                                 : "mocap");
  summary->Add("sensors", sensors);
  JsonObject versions;
  versions.Add("aerobox", AEROBOX_VERSION).Add("mujoco", mj_versionString());
  summary->Add("versions", versions);
}

}  // namespace

JsonObject RunSummary(const FlightSetup& setup, const MissionResult& result,
                      const OutputCounts& counts) {
  const PlanOutcome& plan = result.plan;
  JsonObject summary;
  summary.Add("scenario", setup.name)
      .Add("status", ToString(result.status))
      .Add("seed", static_cast<long long>(setup.seed))
      .Add("map", setup.map.source)
      .Add("vehicle", setup.vehicle_kind)
      .Add("controller", setup.controller.kind);
  if (const std::string measures = setup.ControllerMeasures(); !measures.empty()) {
    summary.Add("controller_measures", measures);
  }
  AddPlan(plan, &summary);
  if (result.status != MissionStatus::kNoPath && plan.trajectory) {
    AddTrajectory(setup, *plan.trajectory, plan, &summary);
  }
  if (result.flown) AddFlight(setup, result, counts, &summary);
  if (setup.HasUnknown()) AddDiscovery(setup, result, &summary);
  AddWorld(setup, &summary);
  return summary;
}

}  // namespace aerobox
