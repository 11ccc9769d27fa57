// The parts the closed loop (FlyTrajectory) is made of, after RotorPy's simulate() and Drake's
// diagrams: each does one job with its own state, and the loop composes them in a fixed order.
// They are the pieces several vehicles in one world and the learning environments step too.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <random>
#include <utility>
#include <vector>

#include "common/flat_output.h"
#include "common/state.h"
#include "control/controller.h"
#include "control/inner_loops.h"
#include "disturbance/aero.h"
#include "disturbance/wind.h"
#include "estimation/sensing.h"
#include "mission/flight.h"
#include "sim/vehicle_physics.h"

namespace aerobox {

// Take-off: a vehicle resting on the floor below the reference's start lifts to it first. The
// reference's clock waits at its start until the vehicle is there (within 2 cm, below 0.3 m/s)
// or 3 s have passed; until the first step without floor contact, the floor is no collision.
// The clock also stands while held (the vehicle turns toward the way ahead before it goes).
class Takeoff {
 public:
  // `start`: the reference's first point [m]; `initial` the vehicle's state, `touching`
  // whether MuJoCo reports a contact before the first step. `holds_clock` false: the reference's
  // clock is the flight's from the first step, whatever the lift and Hold (FlightLoop::
  // shared_clock); the floor is still no collision until the vehicle has left it.
  Takeoff(const Vec3& start, const State& initial, bool touching, bool holds_clock = true);

  // The reference's own time [s] at flight time `t`, ending the lift when the vehicle is there.
  double ReferenceTime(double t, const State& state);
  // From the next step on, the reference's time stands (`on`) or runs again.
  void Hold(bool on) { holding_ = on && holds_clock_; }
  double held() const { return held_; }  // [s] the clock has stood in all
  bool lifting() const { return lifting_; }
  // Whether the vehicle has left the floor (floor contacts are collisions from then on).
  bool airborne() const { return airborne_; }
  void AfterStep(bool any_contact) { airborne_ = airborne_ || !any_contact; }
  double time() const { return time_; }  // [s] of flight when the reference's clock started

 private:
  Vec3 start_;
  bool holds_clock_;
  bool airborne_;
  bool lifting_;
  bool holding_ = false;
  double time_ = 0.0;
  double held_ = 0.0;  // [s]
  double tr_ = 0.0;    // [s] the last reference time
};

// The setpoints along the reference flown: its flat outputs up to snap while it runs, its end
// held after; the yaw from the reference's heading, along the travel (FlightParams::look_ahead,
// yaw_rate), or held. A replacement reference (replanning) is flown from then on, on the same
// clock.
class Setpoints {
 public:
  Setpoints(const Reference& reference, const FlightParams& params, double initial_yaw);

  void Replace(const Reference& next) { current_ = next; }
  const Reference& current() const { return current_; }
  double duration() const { return current_.duration; }
  // The setpoint at flight time `t` and the reference's time `tr` [s].
  FlatOutput At(double t, double tr);
  // With face_travel: whether the reference should wait for the yaw (FlightParams::turn_first);
  // its setpoint is then at rest.
  bool waiting() const { return waiting_; }

 private:
  // The yaw along the travel at `tr` (the reference `here` [m]): toward the reference look_ahead
  // ahead (nearer while the reference's horizontal `speed` [m/s] is slow: the way of its next
  // second, at least 0.3 m), turned from the last at most yaw_rate since it was set (at flight time
  // `t`); the rate it turns at; and how far it has still to turn [rad] (0 when there is no way
  // ahead to turn to).
  struct Turn {
    double yaw, rate, left;
  };
  Turn AlongTravel(double t, double tr, const Vec3& here, double speed);

  Reference current_;
  bool face_travel_;
  double look_ahead_;  // [m]
  double yaw_rate_;    // [rad/s]
  double turn_first_;  // [rad]
  double yaw_;         // [rad] the last one set: held when nothing sets another
  double yaw_time_;    // [s] of flight, when yaw_ was set
  bool waiting_ = false;
};

// The air: the wind where the vehicle is (mean, gusts, turbulence) and the drag it causes,
// applied to the simulation as an external wrench held over each physics step. Off, it does
// nothing and the flight is the still-air one, step for step.
class Air {
 public:
  // The air of `loop` (its wind, or its wind_source in place of it, its drag, vehicle, seed
  // and floor) around a vehicle starting at `p_W` [m].
  Air(const FlightLoop& loop, const Vec3& p_W);

  bool enabled() const { return enabled_; }
  // Before the physics step from `state` at flight time `t` [s] of `step` [s].
  void BeforeStep(double t, double step, const State& state, VehiclePhysics* sim);
  // Takes the wrench off the simulation (at the flight's end).
  void Clear(VehiclePhysics* sim) const;
  const Vec3& wind() const { return wind_W_; }  // [m/s] at the vehicle
  const Wrench& wrench() const { return wrench_; }

 private:
  std::optional<WindField> field_;
  std::function<Vec3(double t, const Vec3& p_W)> source_;
  AeroParams aero_;
  const QuadParams* vehicle_;
  double ground_z_;
  bool enabled_;
  Vec3 wind_W_ = Vec3::Zero();
  Wrench wrench_;
};

// Rotor speed noise (QuadParams::motor_noise), as RotorPy adds its motor_noise_std: once per
// control period, each rotor's produced speed takes N(0, sigma^2) [rad/s], clipped to the
// rotor's range; the motor lag carries it from there. Its own seeded stream.
class MotorNoise {
 public:
  MotorNoise(const QuadParams& vehicle, std::uint64_t seed);
  bool enabled() const { return sigma_ > 0.0; }
  // At a control period's end: perturbs the produced thrusts.
  void Apply(VehiclePhysics* sim);

 private:
  const QuadParams* vehicle_;
  double sigma_;  // [rad/s]
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

// One vehicle in its world below the controller's command, a physics step at a time: the inner
// loops on what the vehicle senses, the air (wind and drag), the physics, then the sensors and the
// estimator; the rotors' noise at each control period's end. The flight loop (FlyTrajectory) steps
// it and so does Python's Simulator.step, so a loop of step() calls flies as run() does, to the
// bit. Its clock starts where it is made.
class VehicleWorld {
 public:
  // From `loop`'s vehicle, inner loops, wind, drag, sensors, seed and floor, around `sim` (which
  // must outlive it) as it is now. Throws std::invalid_argument for bad parameters.
  VehicleWorld(const FlightLoop& loop, VehiclePhysics* sim);

  double time() const { return sim_->time() - t0_; }  // [s] since the world was made
  double step() const { return step_; }               // [s] of one physics step
  State Truth() const { return sim_->VehicleState(); }
  // What a controller flies on: the estimate with sensors on, else `truth`.
  State Seen(const State& truth) const { return sensing_ ? sensing_->Estimate() : truth; }
  // What a controller senses besides the state: the wind at the vehicle, the rotors' thrusts
  // and the acceleration (the IMU's with sensors on, else the physics').
  Surroundings Now() const {
    return {air_.wind(), sim_->RotorThrusts(),
            sensing_ ? sensing_->Acceleration_W() : sim_->LinearAcceleration_W(),
            sensing_.has_value()};
  }
  // The inner loops below `command` for the next physics step, from `seen`; false (zero
  // thrusts) when the command or the state is not finite.
  bool Command(const ControlCommand& command, const State& seen) {
    return inner_.Run(command, seen, step_, &inner_out_);
  }
  // The physics step from `truth` with the rotors' last commands, in the air; the sensors after
  // it. Returns the state after the step. In a world of several vehicles the step is split:
  // each vehicle's BeforePhysics and commands, one step of the world, each one's AfterPhysics.
  State Step(const State& truth) {
    BeforePhysics(truth);
    sim_->Step(inner_out_.mixer.thrusts);
    return AfterPhysics(truth);
  }
  // The air's wrench (and another vehicle's push) on the vehicle for the step from `truth`.
  void BeforePhysics(const State& truth);
  // The sensors after the step from `truth`; the state after it.
  State AfterPhysics(const State& truth);
  // A force [N, world] from the other vehicles (their downwash), added to the air's from the next
  // step on until set again.
  void SetInteractionForce(const Vec3& force_W);
  // At the end of each control period, before the controller's next update: the rotors' noise
  // (MotorNoise), as RotorPy adds it after each of its simulation steps.
  void EndControlPeriod() { motor_noise_.Apply(sim_); }
  // Takes the air's wrench off the simulation (at a flight's end).
  void ClearAir() { air_.Clear(sim_); }

  const InnerOutput& inner() const { return inner_out_; }
  const Air& air() const { return air_; }
  const SensorSuite* sensing() const { return sensing_ ? &*sensing_ : nullptr; }
  VehiclePhysics& sim() const { return *sim_; }

 private:
  VehiclePhysics* sim_;
  double step_;  // [s] physics
  double t0_;    // [s] the simulation's time when the world was made
  InnerLoops inner_;
  Air air_;
  MotorNoise motor_noise_;
  std::optional<SensorSuite> sensing_;
  InnerOutput inner_out_;
  Vec3 interaction_W_ = Vec3::Zero();  // [N]
  bool interacting_ = false;           // a force was set (it may be zero now)
};

// What an observer sees of one physics step: the state before and after it, the rotor
// commands it flew [N], the wind at the vehicle [m/s] and its length [s].
struct PhysicsStepSample {
  const State& before;
  const State& after;
  const Vec4& commanded;
  const Vec3& wind_W;
  double step;
};

// Something that watches a flight without changing it (the metrics, the telemetry, a user's
// recorder): each control step's telemetry row, each physics step, and the result at the end.
class FlightObserver {
 public:
  virtual ~FlightObserver() = default;
  // At a control step; `tracking`: the reference's clock runs (the take-off is over).
  virtual void ControlStep(const TelemetrySample& /*sample*/, bool /*tracking*/) {}
  virtual void PhysicsStep(const PhysicsStepSample& /*step*/) {}
  // At the end: the observer's numbers into the result.
  virtual void Finish(FlightResult* /*result*/) const {}
};

// The numbers of a flight, kept as it goes: tracking from the reference's start, clearance, the
// estimate's error, how hard the rotors worked, speed, distance and the strongest wind.
class FlightMetrics : public FlightObserver {
 public:
  explicit FlightMetrics(const QuadParams& vehicle);
  // The tracking error counts while `tracking`; the clearance and the estimate's error always.
  void ControlStep(const TelemetrySample& sample, bool tracking) override;
  // The rotors' work, the speed, the wind and the distance flown.
  void PhysicsStep(const PhysicsStepSample& step) override;
  // Its tracking, clearance, estimate, effort, speed, distance and wind fields.
  void Finish(FlightResult* result) const override;

 private:
  double max_thrust_;
  double min_thrust_;
  double squared_error_sum_ = 0.0;
  double max_error_ = 0.0;
  long samples_ = 0;
  double min_clearance_;
  double estimate_squared_sum_ = 0.0;
  double estimate_max_error_ = 0.0;
  bool estimated_ = false;
  double peak_rotor_fraction_ = 0.0;
  double saturated_time_ = 0.0;
  double top_speed_ = 0.0;
  double distance_ = 0.0;
  double max_wind_ = 0.0;
};

// A function called with each control step's telemetry row (FlightLoop::telemetry).
class TelemetryCallback : public FlightObserver {
 public:
  explicit TelemetryCallback(std::function<void(const TelemetrySample&)> call)
      : call_(std::move(call)) {}
  void ControlStep(const TelemetrySample& sample, bool) override { call_(sample); }

 private:
  std::function<void(const TelemetrySample&)> call_;
};

// Where a flight stands when the rules judge it: after the control and inner-loop step at
// flight time `t` [s], the reference's own time `tr` [s].
struct FlightMoment {
  double t;
  double tr;
  const State& state;  // the truth
  double error;        // [m] from the setpoint
  bool control_step;   // the controller ran at this step
  const Takeoff& takeoff;
  double duration;       // [s] of the reference flown now
  size_t goals_reached;  // a mission's goals before the last
};

// A rule that ends a flight (termination): the first of a flight's rules to give a status ends
// it. The built-in ones follow; a user's is one more class.
class FlightRule {
 public:
  virtual ~FlightRule() = default;
  virtual std::optional<FlightStatus> Judge(const FlightMoment& now) = 0;
};

// The loop's own rule at each control step (FlightLoop::terminate): kTerminated.
class TerminateRule : public FlightRule {
 public:
  explicit TerminateRule(std::function<bool(double, const State&)> terminate)
      : terminate_(std::move(terminate)) {}
  std::optional<FlightStatus> Judge(const FlightMoment& now) override;

 private:
  std::function<bool(double, const State&)> terminate_;
};

// Further than FlightParams::flyaway_distance from the setpoint: kFlyAway.
class FlyAwayRule : public FlightRule {
 public:
  explicit FlyAwayRule(double distance) : distance_(distance) {}
  std::optional<FlightStatus> Judge(const FlightMoment& now) override;

 private:
  double distance_;  // [m]
};

// Complete (Completion) once the take-off is over: kReachedGoal when every goal of a mission
// was reached in order, kMissedGoal otherwise.
class ArrivalRule : public FlightRule {
 public:
  // `end`: the reference's end [m]; `goals`: how many goals the mission has before it.
  ArrivalRule(const FlightParams& params, const Completion& completion, const Vec3& end,
              size_t goals);
  std::optional<FlightStatus> Judge(const FlightMoment& now) override;

 private:
  double tolerance_;  // [m] at the end
  double speed_;      // [m/s]
  Completion completion_;
  Vec3 end_;
  size_t goals_;
};

// Not arrived within the reference's duration and FlightParams::settle_time after the
// take-off: kTimeout.
class TimeLimitRule : public FlightRule {
 public:
  explicit TimeLimitRule(double settle_time) : settle_time_(settle_time) {}
  std::optional<FlightStatus> Judge(const FlightMoment& now) override;

 private:
  double settle_time_;  // [s]
};

// The parts a flight is flown with, made by the caller (FlyTrajectory below): the vehicle's
// world, its take-off, the rules that end it (asked in order) and its observers. None is owned.
struct FlightParts {
  VehicleWorld* world = nullptr;
  Takeoff* takeoff = nullptr;
  std::vector<FlightRule*> rules;
  std::vector<FlightObserver*> observers;
};

// The built-in parts of a flight of `reference` in `world`, as FlightLoop and FlightParams ask:
// the take-off from where the vehicle is, the loop's terminate rule, fly-away, arrival and the
// time limit, the metrics and the loop's telemetry.
class StandardParts {
 public:
  StandardParts(const Reference& reference, const FlightParams& params, const FlightLoop& loop,
                VehicleWorld* world);
  StandardParts(const StandardParts&) = delete;
  StandardParts& operator=(const StandardParts&) = delete;
  // Its parts; more rules or observers may be added to what it returns.
  FlightParts parts();

 private:
  VehicleWorld* world_;
  Takeoff takeoff_;
  std::optional<TerminateRule> terminate_;
  FlyAwayRule fly_away_;
  ArrivalRule arrival_;
  TimeLimitRule time_limit_;
  FlightMetrics metrics_;
  std::optional<TelemetryCallback> telemetry_;
};

// One flight: the parts, composed one physics step at a time (FlyTrajectory runs one; a world
// of several vehicles runs one per vehicle, stepping the world once between their halves).
class FlightRun {
 public:
  FlightRun(const Reference& reference, const FlightParams& params, const FlightLoop& loop,
            const FlightParts& parts);
  FlightRun(const FlightRun&) = delete;
  FlightRun& operator=(const FlightRun&) = delete;

  // The k-th physics step: BeforePhysics, the vehicle's physics step, AfterPhysics. False when
  // the flight has ended.
  bool Step(long k);
  // Sense, control, judge; the inner loops' rotor commands (world().inner()) and the air for the
  // physics step. False when the flight has ended (then nothing is set for the step).
  bool BeforePhysics(long k);
  // After the physics step: the sensors, the observers, MuJoCo's warnings and the contacts.
  // False when the flight has ended.
  bool AfterPhysics();
  // The result, once the flight has ended (called once).
  FlightResult Finish();

  // After its flight has ended (reached its goal, or timed out), the vehicle may hold the
  // reference's end in a world that others still fly in: the controller and the inner loops go
  // on (on the step the flight ended, from where BeforePhysics left them), nothing is observed;
  // HoldAfterPhysics gives what the vehicle hit, if anything.
  void HoldBeforePhysics(long k);
  std::optional<std::string> HoldAfterPhysics();

  FlightStatus status() const { return result_.status; }
  VehicleWorld& world() const { return *world_; }

 private:
  bool End(FlightStatus status);
  bool Control(double t, double tr, const State& seen);
  void ReachGoals(double t, const State& state);
  void Observe(double t, const State& state, double error);

  const FlightLoop& loop_;
  const FlightParts& parts_;
  VehicleWorld* world_;
  Takeoff& takeoff_;
  double goal_tolerance_;  // [m] a mission's goals ...
  double goal_speed_;      // [m/s]
  int divider_;            // physics steps per control step
  Setpoints setpoints_;
  FlatOutput setpoint_;
  ControlCommand command_;
  std::vector<double> report_;
  FlightResult result_;
  double t0_ = 0.0;      // [s] the world's time when the flight began
  State before_;         // the state the physics step starts from
  long commanded_ = -1;  // the last physics step whose inner loops ran
};

// Flies `reference` with `loop`'s controller and goals through `parts`: the closed loop itself,
// composing them a physics step at a time (the clock starts at the world's time now). Throws
// std::invalid_argument for bad parameters.
FlightResult FlyTrajectory(const Reference& reference, const FlightParams& params,
                           const FlightLoop& loop, const FlightParts& parts);

}  // namespace aerobox
