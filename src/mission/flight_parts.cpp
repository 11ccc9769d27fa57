#include "mission/flight_parts.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tuple>

#include "common/seed.h"

namespace aerobox {
namespace {

// Take-off ends within this distance of the reference's start [m] and below this speed [m/s],
// or after kMaxTakeoff [s] whatever happened.
constexpr double kTakeoffTolerance = 0.02;
constexpr double kTakeoffSpeed = 0.3;
constexpr double kMaxTakeoff = 3.0;

}  // namespace

Takeoff::Takeoff(const Vec3& start, const State& initial, bool touching, bool holds_clock)
    : start_(start), holds_clock_(holds_clock) {
  // on the floor until the first step without floor contact. Before the first step MuJoCo has
  // found no contact for a vehicle resting exactly on the floor: one that sits still right below
  // the trajectory's start (PlaceVehicleAtStart leaves it on the floor) rests there too
  const bool below_start = initial.v_W.norm() < kTakeoffSpeed &&
                           (initial.p_W - start).head<2>().norm() < kTakeoffTolerance &&
                           start.z() - initial.p_W.z() > kTakeoffTolerance;
  airborne_ = !touching && !below_start;
  lifting_ = holds_clock && !airborne_ && (initial.p_W - start).norm() > kTakeoffTolerance;
}

double Takeoff::ReferenceTime(double t, const State& state) {
  if (lifting_ &&
      (((state.p_W - start_).norm() < kTakeoffTolerance && state.v_W.norm() < kTakeoffSpeed) ||
       t >= kMaxTakeoff)) {
    lifting_ = false;
    time_ = t;
  }
  if (lifting_) return 0.0;
  const double tr = t - time_ - held_;
  if (holding_) {
    held_ += tr - tr_;  // the clock stands
    return tr_;
  }
  tr_ = tr;
  return tr_;
}

Setpoints::Setpoints(const Reference& reference, const FlightParams& params, double initial_yaw)
    : current_(reference),
      face_travel_(params.face_travel),
      look_ahead_(params.look_ahead),
      yaw_rate_(params.yaw_rate),
      turn_first_(params.turn_first),
      yaw_(initial_yaw),
      yaw_time_(0.0) {}

FlatOutput Setpoints::At(double t, double tr) {
  const double duration = current_.duration;
  FlatOutput setpoint;
  setpoint.p_W = current_.evaluate(std::min(tr, duration), kPosition);
  waiting_ = false;
  if (tr < duration) {
    setpoint.v_W = current_.evaluate(tr, kVelocity);
    if (current_.heading) {
      std::tie(yaw_, setpoint.yaw_rate) = current_.heading(tr);
    } else if (face_travel_) {
      const Turn turn = AlongTravel(t, tr, setpoint.p_W, setpoint.v_W.head<2>().norm());
      yaw_ = turn.yaw;
      setpoint.yaw_rate = turn.rate;
      waiting_ =
          std::abs(turn.left) > turn_first_ && setpoint.v_W.norm() < FlightParams::kWaitSpeed;
    }
    if (waiting_) {
      setpoint.v_W.setZero();  // at rest where the reference stands
    } else {
      setpoint.a_W = current_.evaluate(tr, kAcceleration);
      setpoint.j_W = current_.evaluate(tr, kJerk);
      setpoint.s_W = current_.evaluate(tr, kSnap);
    }
  } else if (current_.heading) {
    yaw_ = current_.heading(duration).first;
  }
  setpoint.yaw = yaw_;
  return setpoint;
}

Setpoints::Turn Setpoints::AlongTravel(double t, double tr, const Vec3& here, double speed) {
  constexpr double kPi = 3.14159265358979323846;
  constexpr double kStep = 0.02;     // [s] along the reference
  constexpr double kHorizon = 3.0;   // [s] looked ahead at most
  constexpr double kMinimum = 0.15;  // [m] nearer, the direction means nothing: the yaw holds
  constexpr double kLookTime = 1.0;  // [s] a slow reference: the way of its next second ...
  constexpr double kNearest = 0.3;   // [m] ... but at least this far
  const double distance = std::clamp(speed * kLookTime, kNearest, look_ahead_);
  const double elapsed = std::max(0.0, t - yaw_time_);
  yaw_time_ = t;
  Vec3 ahead = here;
  for (double s = tr + kStep; s <= tr + kHorizon; s += kStep) {
    ahead = current_.evaluate(std::min(s, current_.duration), kPosition);
    if ((ahead - here).head<2>().norm() >= distance || s >= current_.duration) break;
  }
  const Eigen::Vector2d toward = (ahead - here).head<2>();
  if (toward.norm() < kMinimum) return {yaw_, 0.0, 0.0};
  const double turn = std::remainder(std::atan2(toward.y(), toward.x()) - yaw_, 2.0 * kPi);
  const double step = std::clamp(turn, -yaw_rate_ * elapsed, yaw_rate_ * elapsed);
  const double rate = elapsed > 0 ? step / elapsed : 0.0;
  return {std::remainder(yaw_ + step, 2.0 * kPi), rate, turn - step};
}

Air::Air(const FlightLoop& loop, const Vec3& p_W)
    : source_(loop.wind_source),
      aero_(loop.aero),
      vehicle_(loop.vehicle),
      ground_z_(loop.ground_z) {
  if (source_) {
    wind_W_ = source_(0.0, p_W);
  } else if (loop.wind.Enabled()) {
    field_.emplace(loop.wind, StreamSeed(loop.seed, SeedStream::kTurbulence));
    wind_W_ = field_->current();
  }
  enabled_ = field_.has_value() || source_ || aero_.Enabled();
}

void Air::BeforeStep(double t, double step, const State& state, VehiclePhysics* sim) {
  if (!enabled_) return;
  // the wind where the vehicle is, and the drag it causes, held over the step
  if (source_) {
    wind_W_ = source_(t, state.p_W);
  } else if (field_) {
    wind_W_ = field_->Step(t, step, state.p_W.z() - ground_z_, state.v_W);
  }
  wrench_ = AerodynamicWrench(*vehicle_, aero_, state, sim->RotorThrusts(), wind_W_);
  sim->SetExternalWrench(wrench_.force_W, wrench_.torque_W);
}

void Air::Clear(VehiclePhysics* sim) const {
  if (enabled_) sim->SetExternalWrench(Vec3::Zero(), Vec3::Zero());
}

MotorNoise::MotorNoise(const QuadParams& vehicle, std::uint64_t seed)
    : vehicle_(&vehicle),
      sigma_(vehicle.motor_noise),
      rng_(StreamSeed(seed, SeedStream::kMotorNoise)) {}

void MotorNoise::Apply(VehiclePhysics* sim) {
  if (!enabled()) return;
  const double low = vehicle_->RotorSpeedFor(vehicle_->MinRotorThrust());
  const double high = vehicle_->RotorSpeedFor(vehicle_->MaxRotorThrust());
  Vec4 thrusts = sim->RotorThrusts();
  for (int i = 0; i < kNumRotors; ++i) {
    const double speed = vehicle_->RotorSpeedFor(thrusts[i]) + sigma_ * normal_(rng_);
    thrusts[i] = vehicle_->ThrustAtSpeed(std::clamp(speed, low, high));
  }
  sim->SetProducedThrusts(thrusts);
}

namespace {

// The physics step [s], once the world's parameters are checked against it.
double CheckedStep(const FlightLoop& loop, const VehiclePhysics& sim) {
  if (loop.vehicle == nullptr) throw std::invalid_argument("VehicleWorld: no vehicle");
  loop.wind.Validate();
  loop.sensors.Validate(sim.timestep());
  return sim.timestep();
}

}  // namespace

VehicleWorld::VehicleWorld(const FlightLoop& loop, VehiclePhysics* sim)
    : sim_(sim),
      step_(CheckedStep(loop, *sim)),
      t0_(sim->time()),
      inner_(loop.inner, *loop.vehicle),
      air_(loop, Truth().p_W),
      motor_noise_(*loop.vehicle, loop.seed) {
  if (loop.sensors.Enabled()) sensing_.emplace(loop.sensors, loop.seed, step_, 0.0, Truth());
}

void VehicleWorld::BeforePhysics(const State& truth) {
  air_.BeforeStep(time(), step_, truth, sim_);
  if (interacting_) {
    const Wrench& air = air_.wrench();
    sim_->SetExternalWrench(air.force_W + interaction_W_, air.torque_W);
  }
}

State VehicleWorld::AfterPhysics(const State& truth) {
  const State after = Truth();
  if (sensing_) sensing_->AfterStep(time(), truth, after, sim_->LinearAcceleration_W());
  return after;
}

void VehicleWorld::SetInteractionForce(const Vec3& force_W) {
  interaction_W_ = force_W;
  interacting_ = true;
}

FlightMetrics::FlightMetrics(const QuadParams& vehicle)
    : max_thrust_(vehicle.MaxRotorThrust()),
      min_thrust_(vehicle.MinRotorThrust()),
      min_clearance_(std::numeric_limits<double>::infinity()) {}

void FlightMetrics::ControlStep(const TelemetrySample& sample, bool tracking) {
  if (tracking) {
    // tracking from when the trajectory's clock starts: the take-off is reported on its own
    const double error = sample.position_error;
    squared_error_sum_ += error * error;
    ++samples_;
    max_error_ = std::max(max_error_, error);
  }
  min_clearance_ = std::min(min_clearance_, sample.clearance);
  if (sample.estimate) {
    const double e = (sample.estimate->estimate.p_W - sample.state.p_W).norm();
    estimated_ = true;
    estimate_squared_sum_ += e * e;
    estimate_max_error_ = std::max(estimate_max_error_, e);
  }
}

void FlightMetrics::PhysicsStep(const PhysicsStepSample& step) {
  // how hard the rotors worked, every physics step
  const Vec4& commanded = step.commanded;
  peak_rotor_fraction_ = std::max(peak_rotor_fraction_, commanded.maxCoeff() / max_thrust_);
  if ((commanded.array() >= max_thrust_ - 1e-9).any() ||
      (commanded.array() <= min_thrust_ + 1e-9).any()) {
    saturated_time_ += step.step;
  }
  top_speed_ = std::max(top_speed_, step.before.v_W.norm());
  max_wind_ = std::max(max_wind_, step.wind_W.norm());
  distance_ += (step.after.p_W - step.before.p_W).norm();
}

void FlightMetrics::Finish(FlightResult* result) const {
  result->rms_error = samples_ > 0 ? std::sqrt(squared_error_sum_ / samples_) : 0.0;
  result->max_error = max_error_;
  result->min_clearance = min_clearance_;
  if (estimated_) {
    result->estimate_max_error = estimate_max_error_;
    if (samples_ > 0) result->estimate_rms_error = std::sqrt(estimate_squared_sum_ / samples_);
  }
  result->peak_rotor_fraction = peak_rotor_fraction_;
  result->saturated_time = saturated_time_;
  result->top_speed = top_speed_;
  result->distance = distance_;
  result->max_wind = max_wind_;
}

std::optional<FlightStatus> TerminateRule::Judge(const FlightMoment& now) {
  if (now.control_step && terminate_(now.t, now.state)) return FlightStatus::kTerminated;
  return std::nullopt;
}

std::optional<FlightStatus> FlyAwayRule::Judge(const FlightMoment& now) {
  if (now.error > distance_) return FlightStatus::kFlyAway;
  return std::nullopt;
}

ArrivalRule::ArrivalRule(const FlightParams& params, const Completion& completion, const Vec3& end,
                         size_t goals)
    : tolerance_(params.goal_tolerance),
      speed_(params.goal_speed),
      completion_(completion),
      end_(end),
      goals_(goals) {}

std::optional<FlightStatus> ArrivalRule::Judge(const FlightMoment& now) {
  if (now.takeoff.lifting()) return std::nullopt;
  const State& s = now.state;
  bool complete = false;
  switch (completion_.kind) {
    case Completion::Kind::kNever:
      break;
    case Completion::Kind::kAtEnd:
      complete =
          now.tr >= now.duration && (s.p_W - end_).norm() < tolerance_ && s.v_W.norm() < speed_;
      break;
    case Completion::Kind::kAtPoint:
      complete = now.tr >= completion_.from &&
                 (s.p_W - completion_.point).norm() < completion_.point_tolerance &&
                 s.v_W.norm() <= completion_.point_speed;
      break;
  }
  if (!complete) return std::nullopt;
  return now.goals_reached == goals_ ? FlightStatus::kReachedGoal : FlightStatus::kMissedGoal;
}

std::optional<FlightStatus> TimeLimitRule::Judge(const FlightMoment& now) {
  // the reference's end on the flight's clock: after the take-off and the clock's holds
  const double end_time = now.duration + settle_time_ + now.takeoff.time() + now.takeoff.held();
  if (now.t >= end_time) return FlightStatus::kTimeout;
  return std::nullopt;
}

StandardParts::StandardParts(const Reference& reference, const FlightParams& params,
                             const FlightLoop& loop, VehicleWorld* world)
    : world_(world),
      takeoff_(reference.evaluate(0.0, kPosition), world->Truth(),
               !world->sim().VehicleContacts().empty(), !loop.shared_clock),
      fly_away_(params.flyaway_distance),
      arrival_(params, loop.completion, reference.evaluate(reference.duration, kPosition),
               loop.goals.size()),
      time_limit_(params.settle_time),
      metrics_(*loop.vehicle) {
  if (loop.terminate) terminate_.emplace(loop.terminate);
  if (loop.telemetry) telemetry_.emplace(loop.telemetry);
}

FlightParts StandardParts::parts() {
  FlightParts parts;
  parts.world = world_;
  parts.takeoff = &takeoff_;
  if (terminate_) parts.rules.push_back(&*terminate_);
  parts.rules.insert(parts.rules.end(), {&fly_away_, &arrival_, &time_limit_});
  parts.observers.push_back(&metrics_);
  if (telemetry_) parts.observers.push_back(&*telemetry_);
  return parts;
}

}  // namespace aerobox
