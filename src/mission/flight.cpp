#include "mission/flight.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "common/fault_injection.h"
#include "common/number_format.h"
#include "common/rates.h"
#include "common/seed.h"
#include "common/stop.h"
#include "scene/scene_mjcf.h"
#include "vehicle/model_names.h"

namespace aerobox {

void FlightParams::Describe(Archive& a) {
  a.Number({"settle_time", "s", "after the trajectory's end, to reach the goal"}, &settle_time, 0,
           3600);
  a.Number({"goal_tolerance", "m", "reached: this close to the goal ..."}, &goal_tolerance, 1e-3,
           100);
  a.Number({"goal_speed", "m/s", "... and this slow"}, &goal_speed, 1e-3, 100);
  a.Number(
      {"flyaway_distance", "m", "this far from the setpoint, the flight is lost (1e12: never)"},
      &flyaway_distance, 0.01, 1e12);
  a.Enum({"yaw", "", "hold the start's yaw, or turn along the travel"}, &face_travel,
         {{false, "hold"}, {true, "travel"}});
}

void FlightParams::Validate() const { ValidateFields(*this, "flight"); }

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
    case FlightStatus::kSimulationWarning:
      return "simulation warning";
    case FlightStatus::kMissedGoal:
      return "missed a goal";
    case FlightStatus::kControllerFailed:
      return "controller failed";
  }
  return "?";
}

Reference ReferenceOf(const PiecewiseTrajectory& trajectory) {
  Reference reference;
  reference.duration = trajectory.duration();
  reference.evaluate = [trajectory](double t, int derivative) -> Vec3 {
    return trajectory.Evaluate3(t, derivative);
  };
  return reference;
}

void PlaceVehicleAtStart(const Map& map, const QuadParams& vehicle, const Vec3& requested,
                         const Vec3& used, Simulation* sim) {
  const Vec3 rest = VehicleRestPosition(map, vehicle, requested);
  if (rest.z() > map.bounds.min.z() + 0.5 * vehicle.collision_size.z() + 1e-9) {
    sim->SetVehicleState(State{used, Vec3::Zero(), Quat::Identity(), Vec3::Zero()});
    sim->SetRotorThrusts(Vec4::Constant(vehicle.HoverThrustPerRotor()));
  }
}

namespace {

// Taking off from the floor: the reference starts once the vehicle is this close to its start
// [m] and this slow [m/s], or after kMaxTakeoff [s] whatever happened.
constexpr double kTakeoffTolerance = 0.02;
constexpr double kTakeoffSpeed = 0.3;
constexpr double kMaxTakeoff = 3.0;

}  // namespace

FlightResult FlyTrajectory(const Reference& reference, const FlightParams& params,
                           const FlightLoop& loop, Simulation* sim) {
  params.Validate();
  if (loop.vehicle == nullptr || loop.controller == nullptr) {
    throw std::invalid_argument("FlyTrajectory: no vehicle or no controller");
  }
  const double step = sim->timestep();
  const int divider = StepsPerPeriod(loop.control_rate, step, "the controller's rate");
  loop.wind.Validate();
  loop.sensors.Validate(step);
  InnerLoops inner(loop.inner, *loop.vehicle);
  Controller& controller = *loop.controller;
  FlightResult result;
  result.min_clearance = std::numeric_limits<double>::infinity();
  result.control_rate = loop.control_rate;

  // the reference flown: the one given, until an updater replaces it
  Reference current = reference;
  double duration = current.duration;
  double end_time = duration + params.settle_time;
  const Vec3 goal = current.evaluate(duration, kPosition);
  double yaw = 0.0;
  {
    const Vec3 x_W = sim->VehicleState().q_WB * Vec3::UnitX();
    yaw = std::atan2(x_W.y(), x_W.x());
  }
  // on the floor until the first step without floor contact. Before the first step MuJoCo has
  // found no contact for a vehicle resting exactly on the floor: one that sits still right below
  // the trajectory's start (PlaceVehicleAtStart leaves it on the floor) rests there too
  const Vec3 start = current.evaluate(0.0, kPosition);
  const State initial = sim->VehicleState();
  const bool below_start = initial.v_W.norm() < kTakeoffSpeed &&
                           (initial.p_W - start).head<2>().norm() < kTakeoffTolerance &&
                           start.z() - initial.p_W.z() > kTakeoffTolerance;
  bool airborne = sim->VehicleContacts().empty() && !below_start;
  bool taking_off = !airborne && (initial.p_W - start).norm() > kTakeoffTolerance;
  double takeoff_time = 0.0;  // [s] of flight when the reference started
  double squared_error_sum = 0.0;
  long samples = 0;

  // an injected fault (common/fault_injection.h): the setpoint turns NaN from this time on
  double nan_from = std::numeric_limits<double>::infinity();
  if (const std::optional<std::string> at = InjectedFault("nonfinite")) {
    if (!ParseNumber(*at, &nan_from)) nan_from = 0.0;
  }

  // the air and the sensors, when asked for
  std::optional<WindField> wind;
  if (loop.wind.Enabled()) {
    wind.emplace(loop.wind, StreamSeed(loop.seed, SeedStream::kTurbulence));
  }
  std::optional<SensorSuite> sensing;
  if (loop.sensors.Enabled()) {
    sensing.emplace(loop.sensors, loop.seed, step, 0.0, sim->VehicleState());
  }
  const bool air = wind.has_value() || loop.aero.Enabled();
  Vec3 wind_W = wind ? wind->current() : Vec3::Zero();
  Wrench aero;
  double estimate_squared_sum = 0.0;

  const double max_thrust = loop.vehicle->MaxRotorThrust();
  const double min_thrust = loop.vehicle->MinRotorThrust();
  FlatOutput setpoint;
  ControlCommand command;
  InnerOutput inner_out;
  std::vector<double> report;
  sim->TakeNewWarnings();  // what loading and placing raised is not the flight's
  const double t0 = sim->time();
  for (long k = 0;; ++k) {
    const double t = sim->time() - t0;
    // Ctrl-C ends the run here, between two physics steps
    ThrowIfStopRequested([t] {
      char at[32];
      std::snprintf(at, sizeof(at), "%.2f", t);
      return "flying (at t = " + std::string(at) + " s)";
    });
    const State state = sim->VehicleState();
    if (!state.p_W.allFinite() || !state.v_W.allFinite() || !state.q_WB.coeffs().allFinite() ||
        !state.w_B.allFinite()) {
      result.status = FlightStatus::kNonFinite;
      break;
    }
    // a vehicle resting on the floor below the trajectory's start lifts to it first: the
    // reference waits at its start until the vehicle is there (or kMaxTakeoff has passed)
    if (taking_off &&
        (((state.p_W - start).norm() < kTakeoffTolerance && state.v_W.norm() < kTakeoffSpeed) ||
         t >= kMaxTakeoff)) {
      taking_off = false;
      takeoff_time = t;
    }
    const double tr = taking_off ? 0.0 : t - takeoff_time;  // the reference's own time [s]

    // the setpoint: the reference's flat outputs when the controller runs, its end held after
    // it; between control steps it is held (the controller sees nothing else)
    const bool control_step = k % divider == 0;
    if (control_step && loop.update_reference && !taking_off) {
      const State seen_now = sensing ? sensing->Estimate() : state;
      if (std::optional<Reference> next = loop.update_reference(
              t, tr, seen_now, static_cast<int>(result.goal_times.size()), current)) {
        current = std::move(*next);
        duration = current.duration;
        end_time = duration + params.settle_time;
        ++result.replans;
      }
    }
    if (control_step) {
      setpoint = FlatOutput();
      setpoint.p_W = current.evaluate(std::min(tr, duration), kPosition);
      if (tr < duration) {
        setpoint.v_W = current.evaluate(tr, kVelocity);
        setpoint.a_W = current.evaluate(tr, kAcceleration);
        setpoint.j_W = current.evaluate(tr, kJerk);
        setpoint.s_W = current.evaluate(tr, kSnap);
        const double speed_xy = setpoint.v_W.head<2>().norm();
        if (current.heading) {
          std::tie(yaw, setpoint.yaw_rate) = current.heading(tr);
        } else if (params.face_travel && speed_xy > 0.2) {
          yaw = std::atan2(setpoint.v_W.y(), setpoint.v_W.x());
          setpoint.yaw_rate =
              (setpoint.v_W.x() * setpoint.a_W.y() - setpoint.v_W.y() * setpoint.a_W.x()) /
              (speed_xy * speed_xy);
        }
      } else if (current.heading) {
        yaw = current.heading(duration).first;
      }
      setpoint.yaw = yaw;
      if (t >= nan_from) setpoint.p_W.x() = std::numeric_limits<double>::quiet_NaN();
    }

    // the controller at its rate, the inner loops every step, on what the sensors tell
    const State seen = sensing ? sensing->Estimate() : state;
    if (control_step) {
      ControlStatus control = controller.Update(t, seen, setpoint, &command);
      if (!control.ok()) {
        const bool failed = control.code == ControlStatus::Code::kFailed;
        result.status = failed ? FlightStatus::kControllerFailed : FlightStatus::kNonFinite;
        result.message = std::move(control.message);
        result.detail = std::move(control.detail);
        break;
      }
    }
    if (!inner.Run(command, seen, step, &inner_out)) {
      result.status = FlightStatus::kNonFinite;
      break;
    }
    // a mission's goals, in order
    if (result.goal_times.size() < loop.goals.size()) {
      const Vec3& next = loop.goals[result.goal_times.size()];
      if ((state.p_W - next).norm() < params.goal_tolerance &&
          (!loop.stop_at_goals || state.v_W.norm() < params.goal_speed)) {
        result.goal_times.push_back(t);
      }
    }
    const double error = (state.p_W - setpoint.p_W).norm();
    if (control_step && !taking_off) {
      // tracking from when the trajectory's clock starts: the take-off is reported on its own
      squared_error_sum += error * error;
      ++samples;
      result.max_error = std::max(result.max_error, error);
    }
    if (control_step) {
      const double c =
          loop.clearance ? loop.clearance(state.p_W) : std::numeric_limits<double>::infinity();
      result.min_clearance = std::min(result.min_clearance, c);
      if (sensing) {
        const double e = (seen.p_W - state.p_W).norm();
        estimate_squared_sum += e * e;
        result.estimate_max_error = std::max(result.estimate_max_error, e);
      }
      if (loop.telemetry) {
        controller.Report(&report);
        loop.telemetry(
            {t, state, setpoint, command, inner_out, sim->RotorThrusts(), error, c, report,
             static_cast<int>(result.goal_times.size()), result.replans, wind_W, aero.force_W,
             sensing ? std::optional<EstimateSample>(sensing->Sample(state)) : std::nullopt});
      }
    }
    if (error > params.flyaway_distance) {
      result.status = FlightStatus::kFlyAway;
      break;
    }
    if (!taking_off && tr >= duration && (state.p_W - goal).norm() < params.goal_tolerance &&
        state.v_W.norm() < params.goal_speed) {
      result.status = result.goal_times.size() == loop.goals.size() ? FlightStatus::kReachedGoal
                                                                    : FlightStatus::kMissedGoal;
      break;
    }
    if (t >= end_time + takeoff_time) {
      result.status = FlightStatus::kTimeout;
      break;
    }

    // how hard the rotors worked, every physics step
    const Vec4& commanded = inner_out.mixer.thrusts;
    result.peak_rotor_fraction =
        std::max(result.peak_rotor_fraction, commanded.maxCoeff() / max_thrust);
    if ((commanded.array() >= max_thrust - 1e-9).any() ||
        (commanded.array() <= min_thrust + 1e-9).any()) {
      result.saturated_time += step;
    }
    result.top_speed = std::max(result.top_speed, state.v_W.norm());
    if (air) {
      // the wind where the vehicle is, and the drag it causes, held over the step
      if (wind) wind_W = wind->Step(t, step, state.p_W.z() - loop.ground_z, state.v_W);
      result.max_wind = std::max(result.max_wind, wind_W.norm());
      aero = AerodynamicWrench(*loop.vehicle, loop.aero, state, sim->RotorThrusts(), wind_W);
      sim->SetExternalWrench(aero.force_W, aero.torque_W);
    }
    sim->Step(commanded);
    ++result.steps;
    const State after = sim->VehicleState();
    result.distance += (after.p_W - state.p_W).norm();
    if (sensing) sensing->AfterStep(sim->time() - t0, state, after, sim->LinearAcceleration_W());
    // a warning means MuJoCo changed or distrusts the state (it resets the data after a bad
    // acceleration): nothing after it can be trusted
    result.message = sim->TakeNewWarnings();
    if (!result.message.empty()) {
      result.status = FlightStatus::kSimulationWarning;
      break;
    }
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
  result.takeoff_time = takeoff_time;
  result.rms_error = samples > 0 ? std::sqrt(squared_error_sum / samples) : 0.0;
  if (sensing && samples > 0) result.estimate_rms_error = std::sqrt(estimate_squared_sum / samples);
  if (air) sim->SetExternalWrench(Vec3::Zero(), Vec3::Zero());
  return result;
}

FlightResult FlyTrajectory(const Reference& reference, const FlightParams& params,
                           const QuadParams& vehicle, const ControllerConfig& control,
                           const std::function<double(const Vec3&)>& clearance,
                           const std::function<void(const TelemetrySample&)>& telemetry,
                           Simulation* sim) {
  control.Validate();
  const std::unique_ptr<Controller> controller = MakeController(control, vehicle);
  FlightLoop loop;
  loop.vehicle = &vehicle;
  loop.controller = controller.get();
  loop.control_rate = control.rate;
  loop.inner = control.inner;
  loop.clearance = clearance;
  loop.telemetry = telemetry;
  return FlyTrajectory(reference, params, loop, sim);
}

}  // namespace aerobox
