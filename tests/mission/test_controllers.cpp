// The controller seam: every command level flies as the cascade does when fed the cascade's own
// inner commands; a controller written here (outside src/) flies the window map through the
// mission; the geometric SE(3) controller tracks the circle and the figure-8; the Crazyflie
// hovers, steps and tracks the circle; MuJoCo's warnings end a flight.
#include <doctest/doctest.h>

#include <cmath>
#include <iostream>
#include <memory>

#include "control/attitude_control.h"
#include "control/cascade.h"
#include "control/mixer.h"
#include "control/position_control.h"
#include "control/rate_control.h"
#include "flight_test_util.h"
#include "mission/mission.h"
#include "scenario/scenario.h"
#include "test_support.h"

namespace aerobox {
namespace {

using testing::Circle;
using testing::CircleDuration;
using testing::Eight;
using testing::EightDuration;
using testing::FromFunction;
using testing::RoomAt;
using testing::Track;

Track Fly(const Reference& reference, Simulation* sim, Controller* controller, double rate,
          const QuadParams& vehicle = QuadParams()) {
  Track track;
  FlightParams params;
  params.settle_time = 3.0;
  FlightLoop loop;
  loop.vehicle = &vehicle;
  loop.controller = controller;
  loop.control_rate = rate;
  loop.telemetry = [&track](const TelemetrySample& s) { track.samples.push_back(s); };
  track.result = FlyTrajectory(reference, params, loop, sim);
  return track;
}

Track FlyKind(const std::string& kind, const Reference& reference, Simulation* sim,
              const QuadParams& vehicle = QuadParams()) {
  ControllerConfig config;
  config.kind = kind;
  config.rate = kind == "se3" ? 500.0 : 250.0;
  const std::unique_ptr<Controller> controller = MakeController(config, vehicle);
  return Fly(reference, sim, controller.get(), config.rate, vehicle);
}

// PX4's cascade run whole in the test at 1 kHz, answering at `level`: the position loop every
// 4th call (as aerobox's cascade at 250 Hz), the stages down to `level` every call, with the
// same gains and the same jerk feed-forward as aerobox's inner loops. Fed to aerobox's inner loops,
// every level must fly the cascade's flight.
class CascadeAtLevel : public Controller {
 public:
  CascadeAtLevel(CommandLevel level, const QuadParams& vehicle)
      : level_(level),
        position_(PositionControlParams(), vehicle.mass),
        attitude_(AttitudeControlParams()),
        rate_(RateControlParams(), vehicle.inertia),
        mixer_(vehicle) {
    last_.thrust = vehicle.mass * kGravity;
  }

  ControlStatus Update(double, const State& state, const FlatOutput& setpoint,
                       ControlCommand* command) override {
    if (calls_++ % 4 == 0) {
      PositionSetpoint target{setpoint.p_W, setpoint.v_W, setpoint.a_W, setpoint.yaw};
      if (!position_.Update(target, state.p_W, state.v_W, state.q_WB, 0.004, &last_))
        return ControlStatus::NonFinite();
      feed_forward_ = RateFeedForward(setpoint, last_.q_WB);
    }
    command->level = level_;
    command->thrust = last_.thrust;
    command->q_WB = last_.q_WB;
    command->rate_B = feed_forward_;
    if (level_ == CommandLevel::kThrustAttitude) return ControlStatus::Ok();
    if (!attitude_.Update(state.q_WB, last_.q_WB, &command->rate_B))
      return ControlStatus::NonFinite();
    command->rate_B += feed_forward_;
    if (level_ == CommandLevel::kThrustRates) return ControlStatus::Ok();
    if (!rate_.Update(command->rate_B, state.w_B, 0.001, saturated_, &command->moment_B)) {
      return ControlStatus::NonFinite();
    }
    MixerOutput mixed;
    if (!mixer_.Mix(last_.thrust, command->moment_B, &mixed)) return ControlStatus::NonFinite();
    saturated_ = mixed.saturated();
    command->rotor_thrusts = mixed.thrusts;
    return ControlStatus::Ok();
  }

 private:
  CommandLevel level_;
  PositionController position_;
  AttitudeController attitude_;
  RateController rate_;
  Mixer mixer_;
  AttitudeSetpoint last_;
  Vec3 feed_forward_ = Vec3::Zero();  // body rates from the jerk, held with the position loop's
  long calls_ = 0;
  bool saturated_ = false;
};

// A controller of the test's own: PD on position to a thrust vector, commanded as thrust and
// attitude (aerobox's inner loops do the rest). Not PX4's cascade, not SE(3).
class PdController : public Controller {
 public:
  explicit PdController(double mass) : mass_(mass) {}
  ControlStatus Update(double, const State& state, const FlatOutput& sp,
                       ControlCommand* command) override {
    const Vec3 a =
        6.0 * (sp.p_W - state.p_W) + 4.0 * (sp.v_W - state.v_W) + sp.a_W + Vec3(0, 0, kGravity);
    if (!a.allFinite() || !state.q_WB.coeffs().allFinite()) return ControlStatus::NonFinite();
    ++updates_;
    command->level = CommandLevel::kThrustAttitude;
    command->thrust = mass_ * a.dot(state.q_WB * Vec3::UnitZ());
    command->q_WB = Quat::FromTwoVectors(Vec3::UnitZ(), a.normalized());
    return ControlStatus::Ok();
  }
  std::vector<std::string> ReportColumns() const override { return {"pd_updates"}; }
  void Report(std::vector<double>* values) const override {
    *values = {static_cast<double>(updates_)};
  }

 private:
  double mass_;
  long updates_ = 0;
};

// Counts what the mission tells its observers.
struct Counter : MissionObserver {
  int scenes = 0, plans = 0, starts = 0, samples = 0, ends = 0;
  double last_report = 0;
  void OnScene(Simulation&, const std::vector<bool>&) override { ++scenes; }
  void OnPlan(const PlanOutcome&) override { ++plans; }
  void OnFlightStart(const Simulation&, const Controller&) override { ++starts; }
  void OnSample(const TelemetrySample& s) override {
    ++samples;
    if (!s.report.empty()) last_report = s.report[0];
  }
  void OnFlightEnd(const Simulation&, const FlightResult&) override { ++ends; }
};

}  // namespace

TEST_CASE("each command level fed the cascade's own inner commands flies the cascade's flight") {
  const Reference eight = FromFunction(EightDuration(), Eight);
  Simulation reference_sim = RoomAt(Eight(0));
  const Track cascade = FlyKind("cascade", eight, &reference_sim);
  REQUIRE(cascade.result.status == FlightStatus::kReachedGoal);
  for (const CommandLevel level : {CommandLevel::kThrustAttitude, CommandLevel::kThrustRates,
                                   CommandLevel::kThrustMoment, CommandLevel::kRotorThrusts}) {
    CAPTURE(ToString(level));
    Simulation sim = RoomAt(Eight(0));
    CascadeAtLevel controller(level, QuadParams());
    const Track track = Fly(eight, &sim, &controller, 1000.0);
    REQUIRE(track.result.status == FlightStatus::kReachedGoal);
    // the same flight: the same arithmetic in another place, so the paths agree to rounding
    // (1 um over 10 s of flight); the cascade samples every 4th step, these every step
    double worst = 0;
    for (size_t i = 0; i < cascade.samples.size() && 4 * i < track.samples.size(); ++i) {
      worst =
          std::max(worst, (cascade.samples[i].state.p_W - track.samples[4 * i].state.p_W).norm());
    }
    CHECK(worst < 1e-6);
    CHECK(track.result.time == doctest::Approx(cascade.result.time).epsilon(1e-3));
  }
}

TEST_CASE("the geometric SE(3) controller tracks the circle and the figure-8") {
  Simulation circle_sim = RoomAt(Circle(0));
  const Track circle = FlyKind("se3", FromFunction(CircleDuration(), Circle), &circle_sim);
  Simulation eight_sim = RoomAt(Eight(0));
  const Track eight = FlyKind("se3", FromFunction(EightDuration(), Eight), &eight_sim);
  std::cout << "se3: circle RMS " << circle.result.rms_error * 100 << " cm (max "
            << circle.result.max_error * 100 << "), figure-8 RMS " << eight.result.rms_error * 100
            << " cm (max " << eight.result.max_error * 100 << ")\n";
  CHECK(circle.result.status == FlightStatus::kReachedGoal);
  CHECK(eight.result.status == FlightStatus::kReachedGoal);
  // the cascade's bounds in test_flight.cpp: 3 cm on the circle, 5 cm on the figure-8
  CHECK(circle.result.rms_error < 0.03);
  CHECK(eight.result.rms_error < 0.05);
  // its own telemetry columns: the attitude error stays small on a smooth path
  REQUIRE(circle.samples.back().report.size() == 6);
  for (const TelemetrySample& s : circle.samples) CHECK(Vec3(s.report.data()).norm() < 0.1);
}

TEST_CASE("the Crazyflie hovers, steps and tracks the 1 m circle") {
  const QuadParams cf = *BuiltinVehicle("crazyflie");
  for (const char* kind : {"cascade", "se3"}) {
    CAPTURE(kind);
    Simulation hover_sim = RoomAt(Vec3(0.05, -0.05, 0.97), Map(), cf);
    hover_sim.SetRotorThrusts(Vec4::Constant(cf.HoverThrustPerRotor()));
    const Track hover =
        FlyKind(kind, FromFunction(5.0, [](double) { return Vec3(0, 0, 1); }), &hover_sim, cf);
    double worst = 0;
    for (const TelemetrySample& s : hover.samples) {
      if (s.t >= 3.0) worst = std::max(worst, s.position_error);
    }
    CHECK(hover.result.status == FlightStatus::kReachedGoal);
    CHECK(worst < 0.01);

    Simulation step_sim = RoomAt(Vec3(0, 0, 1), Map(), cf);
    step_sim.SetRotorThrusts(Vec4::Constant(cf.HoverThrustPerRotor()));
    const Track step = FlyKind(
        kind, FromFunction(6.0, [](double t) { return t < 1.0 ? Vec3(0, 0, 1) : Vec3(1, 0, 1); }),
        &step_sim, cf);
    double overshoot = 0;
    for (const TelemetrySample& s : step.samples)
      overshoot = std::max(overshoot, s.state.p_W.x() - 1);
    CHECK(step.result.status == FlightStatus::kReachedGoal);
    CHECK(overshoot < 0.2);

    Simulation circle_sim = RoomAt(Circle(0), Map(), cf);
    circle_sim.SetRotorThrusts(Vec4::Constant(cf.HoverThrustPerRotor()));
    const Track circle = FlyKind(kind, FromFunction(CircleDuration(), Circle), &circle_sim, cf);
    std::cout << "crazyflie " << kind << ": hover " << worst * 1e3 << " mm after 3 s, step "
              << overshoot * 100 << " % overshoot, circle RMS " << circle.result.rms_error * 100
              << " cm\n";
    CHECK(circle.result.status == FlightStatus::kReachedGoal);
    CHECK(circle.result.rms_error < 0.06);
  }
}

TEST_CASE("a controller written outside src/ flies the window map through the mission") {
  FlightSetup setup =
      LoadFlightSetup((testing::SourceDir() / "scenes" / "window" / "scenario.toml").string(), {});
  // the seam is under test, not how a PD controller without feed-forward of jerk keeps up at
  // the vehicle's limits: the trajectory keeps to 2 m/s (the speed this test was written at)
  setup.planning.trajectory.max_speed = 2.0;
  PdController controller(setup.vehicle.mass);
  Counter counter;
  MissionParts parts;
  parts.controller = &controller;
  parts.observers = {&counter};
  const MissionResult result = RunMission(setup, parts);
  CAPTURE(result.flight.rms_error);
  REQUIRE(result.status == MissionStatus::kReachedGoal);
  CHECK(result.flight.min_clearance > 0);
  CHECK(result.flight.rms_error < 0.10);
  CHECK(counter.scenes == 1);
  CHECK(counter.plans == 1);
  CHECK(counter.starts == 1);
  CHECK(counter.ends == 1);
  CHECK(counter.samples > 1000);
  CHECK(counter.last_report == counter.samples);  // its own column reached the observers

  // registered by name, it is chosen as the built-ins are
  if (Controllers().Find("test_pd") == nullptr) {
    Controllers().Register("test_pd", [](const ControllerConfig&, const QuadParams& vehicle) {
      return std::make_unique<PdController>(vehicle.mass);
    });
  }
  setup.controller.kind = "test_pd";
  CHECK(RunMission(setup, MissionParts()).status == MissionStatus::kReachedGoal);
}

TEST_CASE("a MuJoCo warning ends the flight with its own status") {
  Simulation sim = RoomAt(Vec3(0, 0, 1));
  // a velocity beyond MuJoCo's limit: it resets the data and warns at the first step
  sim.SetVehicleState(State{Vec3(0, 0, 1), Vec3(1e11, 0, 0), Quat::Identity(), Vec3::Zero()});
  ControllerConfig config;
  FlightParams params;
  params.flyaway_distance = 1e12;  // let the flight reach the step
  const FlightResult result = FlyTrajectory(FromFunction(2.0, [](double) { return Vec3(0, 0, 1); }),
                                            params, QuadParams(), config, {}, {}, &sim);
  CHECK(result.status == FlightStatus::kSimulationWarning);
  CAPTURE(result.message);
  CHECK(result.message.find("QVEL") != std::string::npos);
  CHECK(result.steps == 1);
}

}  // namespace aerobox

namespace aerobox {

TEST_CASE("a map with many boxes keeps only those near the route in its scene, as a city does") {
  // a 40 x 40 m forest of 900 trees, 1.3 m apart: far more than kCullAboveBoxes
  Map map;
  map.name = "forest";
  map.source = "forest.txt";
  map.bounds = {Vec3(0, 0, 0), Vec3(40, 40, 4)};
  for (int i = 0; i < 30; ++i) {
    for (int j = 0; j < 30; ++j) {
      const Vec3 c(1.5 + 1.3 * i, 1.5 + 1.3 * j, 2);
      map.boxes.push_back({{c - Vec3(0.15, 0.15, 2), c + Vec3(0.15, 0.15, 2)},
                           Vec3(0, 0.6, 0),
                           "tree_" + std::to_string(30 * i + j),
                           30 * i + j + 2});
    }
  }
  FlightSetup setup;
  setup.name = "forest";
  setup.map = map;
  setup.start = Vec3(0.5, 0.5, 1);
  setup.goal = Vec3(8, 1.2, 1);
  struct Scene : MissionObserver {
    size_t kept = 0, flags = 0;
    void OnScene(Simulation&, const std::vector<bool>& k) override {
      flags = k.size();
      kept = static_cast<size_t>(std::count(k.begin(), k.end(), true));
    }
  } scene;
  MissionParts parts;
  parts.observers = {&scene};
  const MissionResult result = RunMission(setup, parts);
  CHECK(result.status == MissionStatus::kReachedGoal);
  CHECK(scene.flags == map.boxes.size());
  CHECK(scene.kept > 0);
  CHECK(scene.kept < map.boxes.size());  // the trees far from the route are scenery
}

}  // namespace aerobox
