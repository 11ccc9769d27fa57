#include "mission/flight.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "common/number_format.h"
#include "common/rates.h"
#include "common/stop.h"
#include "mission/flight_parts.h"
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
  a.Number({"look_ahead", "m", "yaw \"travel\": turns toward the reference this far ahead"},
           &look_ahead, 0.05, 100);
  a.Degrees({"yaw_rate", "deg/s", "yaw \"travel\": turns at most this fast"}, &yaw_rate, 1, 3600);
  a.Degrees({"turn_first", "deg",
             "yaw \"travel\": below 0.25 m/s the reference waits while the yaw is further than "
             "this from the way ahead (180: never)"},
            &turn_first, 1, 180);
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
    case FlightStatus::kTerminated:
      return "terminated";
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
                         const Vec3& used, VehiclePhysics* sim) {
  const Vec3 rest = VehicleRestPosition(map, vehicle, requested);
  if (rest.z() > map.bounds.min.z() + 0.5 * vehicle.collision_size.z() + 1e-9) {
    sim->SetVehicleState(State{used, Vec3::Zero(), Quat::Identity(), Vec3::Zero()});
    sim->SetRotorThrusts(Vec4::Constant(vehicle.HoverThrustPerRotor()));
  }
}

namespace {

// The first contact of the vehicle with anything but the floor it has not yet left, if any.
std::optional<std::string> Collision(const std::vector<VehicleContact>& contacts, bool airborne) {
  for (const VehicleContact& contact : contacts) {
    if (!airborne && contact.other_geom == model_names::kFloorGeom) continue;
    return contact.other_geom;
  }
  return std::nullopt;
}

double YawOf(const State& state) {
  const Vec3 x_W = state.q_WB * Vec3::UnitX();
  return std::atan2(x_W.y(), x_W.x());
}

}  // namespace

FlightRun::FlightRun(const Reference& reference, const FlightParams& params, const FlightLoop& loop,
                     const FlightParts& parts)
    : loop_(loop),
      parts_(parts),
      world_(parts.world),
      takeoff_(*parts.takeoff),
      goal_tolerance_(params.goal_tolerance),
      goal_speed_(params.goal_speed),
      divider_(StepsPerPeriod(loop.control_rate, world_->step(), "the controller's rate")),
      setpoints_(reference, params, YawOf(world_->Truth())) {
  result_.control_rate = loop.control_rate;
  world_->sim().TakeNewWarnings();  // what loading and placing raised is not the flight's
  t0_ = world_->time();
}

bool FlightRun::Step(long k) {
  if (!BeforePhysics(k)) return false;
  world_->sim().Step(world_->inner().mixer.thrusts);
  return AfterPhysics();
}

// Sense, control, judge. False when it has ended.
bool FlightRun::BeforePhysics(long k) {
  const double t = world_->time() - t0_;
  // Ctrl-C ends the run here, between two physics steps
  ThrowIfStopRequested([t] {
    char at[32];
    std::snprintf(at, sizeof(at), "%.2f", t);
    return "flying (at t = " + std::string(at) + " s)";
  });
  const bool control_step = k % divider_ == 0;
  if (control_step && k > 0) world_->EndControlPeriod();
  const State state = world_->Truth();
  if (!state.AllFinite()) return End(FlightStatus::kNonFinite);
  const double tr = takeoff_.ReferenceTime(t, state);  // the reference's own time [s]
  const State seen = world_->Seen(state);              // what the controller sees
  if (control_step && !Control(t, tr, seen)) return false;
  // the inner loops every step, on the command held between control steps
  commanded_ = k;
  if (!world_->Command(command_, seen)) return End(FlightStatus::kNonFinite);
  ReachGoals(t, state);
  const double error = (state.p_W - setpoint_.p_W).norm();
  if (control_step) Observe(t, state, error);
  const FlightMoment now{t,
                         tr,
                         state,
                         error,
                         control_step,
                         takeoff_,
                         setpoints_.duration(),
                         result_.goal_times.size()};
  for (FlightRule* rule : parts_.rules) {
    if (const std::optional<FlightStatus> verdict = rule->Judge(now)) return End(*verdict);
  }
  before_ = state;
  world_->BeforePhysics(state);
  return true;
}

FlightResult FlightRun::Finish() {
  result_.time = world_->time() - t0_;
  result_.end_position = world_->Truth().p_W;
  result_.takeoff_time = takeoff_.time();
  for (const FlightObserver* observer : parts_.observers) observer->Finish(&result_);
  world_->ClearAir();
  return result_;
}

bool FlightRun::End(FlightStatus status) {
  result_.status = status;
  return false;
}

// At the controller's rate: a replaced reference (replanning), the setpoint, the command.
bool FlightRun::Control(double t, double tr, const State& seen) {
  if (loop_.update_reference && !takeoff_.lifting()) {
    if (std::optional<Reference> next = loop_.update_reference(
            t, tr, seen, static_cast<int>(result_.goal_times.size()), setpoints_.current())) {
      setpoints_.Replace(*next);
      ++result_.replans;
    }
  }
  setpoint_ = setpoints_.At(t, tr);
  takeoff_.Hold(setpoints_.waiting());
  if (t >= loop_.nonfinite_setpoint_from) {
    setpoint_.p_W.x() = std::numeric_limits<double>::quiet_NaN();
  }
  loop_.controller->Sense(world_->Now());
  ControlStatus control = loop_.controller->Update(t, seen, setpoint_, &command_);
  if (control.ok()) return true;
  result_.message = std::move(control.message);
  result_.detail = std::move(control.detail);
  return End(control.code == ControlStatus::Code::kFailed ? FlightStatus::kControllerFailed
                                                          : FlightStatus::kNonFinite);
}

// A mission's goals, in order.
void FlightRun::ReachGoals(double t, const State& state) {
  if (result_.goal_times.size() >= loop_.goals.size()) return;
  const Vec3& next = loop_.goals[result_.goal_times.size()];
  if ((state.p_W - next).norm() < goal_tolerance_ &&
      (!loop_.stop_at_goals || state.v_W.norm() < goal_speed_)) {
    result_.goal_times.push_back(t);
  }
}

// At the controller's rate: the telemetry row, to every observer.
void FlightRun::Observe(double t, const State& state, double error) {
  const double c =
      loop_.clearance ? loop_.clearance(state.p_W) : std::numeric_limits<double>::infinity();
  const SensorSuite* sensing = world_->sensing();
  loop_.controller->Report(&report_);
  const TelemetrySample sample{
      t,
      state,
      setpoint_,
      command_,
      world_->inner(),
      world_->sim().RotorThrusts(),
      error,
      c,
      report_,
      static_cast<int>(result_.goal_times.size()),
      result_.replans,
      loop_.map_size ? loop_.map_size() : OccupancySize{},
      world_->air().wind(),
      world_->air().wrench().force_W,
      sensing ? std::optional<EstimateSample>(sensing->Sample(state)) : std::nullopt};
  for (FlightObserver* observer : parts_.observers) {
    observer->ControlStep(sample, !takeoff_.lifting());
  }
}

// After the physics step, in the air: what MuJoCo says of it (a warning, a contact).
bool FlightRun::AfterPhysics() {
  const State after = world_->AfterPhysics(before_);
  const PhysicsStepSample step{before_, after, world_->inner().mixer.thrusts, world_->air().wind(),
                               world_->step()};
  for (FlightObserver* observer : parts_.observers) observer->PhysicsStep(step);
  ++result_.steps;
  // a warning means MuJoCo changed or distrusts the state (it resets the data after a bad
  // acceleration): nothing after it can be trusted
  VehiclePhysics& sim = world_->sim();
  result_.message = sim.TakeNewWarnings();
  if (!result_.message.empty()) return End(FlightStatus::kSimulationWarning);
  const std::vector<VehicleContact> contacts = sim.VehicleContacts();
  if (const std::optional<std::string> hit = Collision(contacts, takeoff_.airborne())) {
    result_.obstacle = *hit;
    return End(FlightStatus::kCollision);
  }
  takeoff_.AfterStep(!contacts.empty());
  return true;
}

void FlightRun::HoldBeforePhysics(long k) {
  const State state = world_->Truth();
  before_ = state;
  if (commanded_ != k) {  // not on the step the flight ended: BeforePhysics has run the loops
    commanded_ = k;
    const double t = world_->time() - t0_;
    const bool control_step = k % divider_ == 0;
    if (control_step) world_->EndControlPeriod();
    const State seen = world_->Seen(state);
    if (control_step) {
      setpoint_ = setpoints_.At(t, takeoff_.ReferenceTime(t, state));
      loop_.controller->Sense(world_->Now());
      loop_.controller->Update(t, seen, setpoint_, &command_);
    }
    world_->Command(command_, seen);
  }
  world_->BeforePhysics(state);
}

std::optional<std::string> FlightRun::HoldAfterPhysics() {
  world_->AfterPhysics(before_);
  const std::vector<VehicleContact> contacts = world_->sim().VehicleContacts();
  const std::optional<std::string> hit = Collision(contacts, takeoff_.airborne());
  takeoff_.AfterStep(!contacts.empty());
  return hit;
}

namespace {

void CheckFlight(const FlightParams& params, const FlightLoop& loop) {
  params.Validate();
  if (loop.vehicle == nullptr || loop.controller == nullptr) {
    throw std::invalid_argument("FlyTrajectory: no vehicle or no controller");
  }
}

}  // namespace

FlightResult FlyTrajectory(const Reference& reference, const FlightParams& params,
                           const FlightLoop& loop, const FlightParts& parts) {
  CheckFlight(params, loop);
  if (parts.world == nullptr || parts.takeoff == nullptr) {
    throw std::invalid_argument("FlyTrajectory: no world or no take-off");
  }
  FlightRun run(reference, params, loop, parts);
  for (long k = 0; run.Step(k); ++k) {
  }
  return run.Finish();
}

FlightResult FlyTrajectory(const Reference& reference, const FlightParams& params,
                           const FlightLoop& loop, VehicleWorld* world) {
  CheckFlight(params, loop);
  StandardParts parts(reference, params, loop, world);
  return FlyTrajectory(reference, params, loop, parts.parts());
}

FlightResult FlyTrajectory(const Reference& reference, const FlightParams& params,
                           const FlightLoop& loop, Simulation* sim) {
  VehicleWorld world(loop, sim);  // checks the vehicle, the wind and the sensors
  return FlyTrajectory(reference, params, loop, &world);
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
