// The parts the closed loop (FlyTrajectory) is made of, after RotorPy's simulate() and Drake's
// diagrams: each does one job with its own state, and the loop composes them in a fixed order.
// They are the pieces several vehicles in one world and the learning environments step too.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <random>

#include "common/flat_output.h"
#include "common/state.h"
#include "control/controller.h"
#include "control/inner_loops.h"
#include "disturbance/aero.h"
#include "disturbance/wind.h"
#include "estimation/sensing.h"
#include "mission/flight.h"
#include "sim/simulation.h"

namespace aerobox {

// Take-off: a vehicle resting on the floor below the reference's start lifts to it first. The
// reference's clock waits at its start until the vehicle is there (within 2 cm, below 0.3 m/s)
// or 3 s have passed; until the first step without floor contact, the floor is no collision.
class Takeoff {
 public:
  // `start`: the reference's first point [m]; `initial` the vehicle's state, `touching`
  // whether MuJoCo reports a contact before the first step.
  Takeoff(const Vec3& start, const State& initial, bool touching);

  // The reference's own time [s] at flight time `t`, ending the lift when the vehicle is there.
  double ReferenceTime(double t, const State& state);
  bool lifting() const { return lifting_; }
  // Whether the vehicle has left the floor (floor contacts are collisions from then on).
  bool airborne() const { return airborne_; }
  void AfterStep(bool any_contact) { airborne_ = airborne_ || !any_contact; }
  double time() const { return time_; }  // [s] of flight when the reference's clock started

 private:
  Vec3 start_;
  bool airborne_;
  bool lifting_;
  double time_ = 0.0;
};

// The setpoints along the reference flown: its flat outputs up to snap while it runs, its end
// held after; the yaw from the reference's heading, along the travel, or held. A replacement
// reference (replanning) is flown from then on, on the same clock.
class Setpoints {
 public:
  Setpoints(const Reference& reference, bool face_travel, double initial_yaw);

  void Replace(const Reference& next) { current_ = next; }
  const Reference& current() const { return current_; }
  double duration() const { return current_.duration; }
  // The setpoint at the reference's time `tr` [s].
  FlatOutput At(double tr);

 private:
  Reference current_;
  bool face_travel_;
  double yaw_;  // [rad] the last one set: held when nothing sets another
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
  void BeforeStep(double t, double step, const State& state, Simulation* sim);
  // Takes the wrench off the simulation (at the flight's end).
  void Clear(Simulation* sim) const;
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
  void Apply(Simulation* sim);

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
  VehicleWorld(const FlightLoop& loop, Simulation* sim);

  double time() const { return sim_->time() - t0_; }  // [s] since the world was made
  double step() const { return step_; }               // [s] of one physics step
  State Truth() const { return sim_->VehicleState(); }
  // What a controller flies on: the estimate with sensors on, else `truth`.
  State Seen(const State& truth) const { return sensing_ ? sensing_->Estimate() : truth; }
  // What a controller senses besides the state: the wind at the vehicle and the rotors' thrusts.
  Surroundings Now() const { return {air_.wind(), sim_->RotorThrusts()}; }
  // The inner loops below `command` for the next physics step, from `seen`; false (zero
  // thrusts) when the command or the state is not finite.
  bool Command(const ControlCommand& command, const State& seen) {
    return inner_.Run(command, seen, step_, &inner_out_);
  }
  // The physics step from `truth` with the rotors' last commands, in the air; the sensors after
  // it. Returns the state after the step.
  State Step(const State& truth);
  // At the end of each control period, before the controller's next update: the rotors' noise
  // (MotorNoise), as RotorPy adds it after each of its simulation steps.
  void EndControlPeriod() { motor_noise_.Apply(sim_); }
  // Takes the air's wrench off the simulation (at a flight's end).
  void ClearAir() { air_.Clear(sim_); }

  const InnerOutput& inner() const { return inner_out_; }
  const Air& air() const { return air_; }
  const SensorSuite* sensing() const { return sensing_ ? &*sensing_ : nullptr; }
  Simulation& sim() const { return *sim_; }

 private:
  Simulation* sim_;
  double step_;  // [s] physics
  double t0_;    // [s] the simulation's time when the world was made
  InnerLoops inner_;
  Air air_;
  MotorNoise motor_noise_;
  std::optional<SensorSuite> sensing_;
  InnerOutput inner_out_;
};

// The numbers of a flight, kept as it goes: tracking from the reference's start, clearance, the
// estimate's error, how hard the rotors worked, speed, distance and the strongest wind.
class FlightMetrics {
 public:
  explicit FlightMetrics(const QuadParams& vehicle);
  // At a control step: `error` [m] counts for tracking when `tracking` (the reference's clock
  // runs); `clearance` [m]; the estimate's error [m] when there is an estimate.
  void ControlStep(double error, bool tracking, double clearance,
                   std::optional<double> estimate_error);
  // Before each physics step of `step` [s]: the rotor commands [N], the speed, the wind [m/s].
  void PhysicsStep(const Vec4& commanded, double step, const State& state, const Vec3& wind_W);
  // After it: the distance flown.
  void Moved(const State& before, const State& after);
  // Into `result`: its tracking, clearance, estimate, effort, speed, distance and wind fields.
  void Fill(FlightResult* result) const;

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

}  // namespace aerobox
