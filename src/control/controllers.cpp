#include "control/controllers.h"

#include <cmath>
#include <stdexcept>

#include "common/drag.h"
#include "common/number_format.h"
#include "control/cascade.h"
#include "control/indi_control.h"

namespace aerobox {

void ControllerConfig::Describe(Archive& a) {
  a.Number({"rate", "Hz", "how often the controller runs; divides the 1000 Hz physics rate"}, &rate,
           1, 1000);
  a.Boolean({"drag_feedforward", "", "feed the vehicle's own drag forward (on with [aero])"},
            &drag_feedforward);
  // the cascade (kind "cascade"): the position and velocity loops
  PositionControlParams& c = cascade;
  a.Vector({"position_gain", "1/s", "cascade: velocity setpoint per metre of error"},
           &c.position_gain, 0, 1e5);
  a.Vector({"velocity_gain", "1/s", "cascade: acceleration per m/s of error"}, &c.velocity_gain, 0,
           1e5);
  a.Vector({"velocity_integral", "1/s^2", "cascade: the velocity error's integral"},
           &c.velocity_integral, 0, 1e5);
  a.Vector({"velocity_derivative", "", "cascade: on the measured acceleration"},
           &c.velocity_derivative, 0, 1e5);
  a.Vector({"velocity_integral_limit", "m/s^2", "cascade: the integral term's anti-windup clamp"},
           &c.integral_limit, 0, 1e5);
  a.Number({"max_speed_horizontal", "m/s", "cascade: the velocity setpoint's limit"},
           &c.max_speed_horizontal, 0.01, 100);
  a.Number({"max_speed_vertical", "m/s", "cascade: ... vertical"}, &c.max_speed_vertical, 0.01,
           100);
  a.Number({"max_accel_horizontal", "m/s^2", "cascade: the acceleration setpoint's limit"},
           &c.max_accel_horizontal, 0.01, 100);
  a.Number({"max_accel_vertical", "m/s^2", "cascade: ... vertical"}, &c.max_accel_vertical, 0.01,
           100);
  a.Number({"max_tilt", "rad", "between the thrust and the world's z (cascade and se3)"},
           &c.max_tilt, 0.01, 1.5);
  a.Number({"min_thrust_fraction", "", "cascade: of the weight, the least thrust"},
           &c.min_thrust_fraction, 0.01, 0.99);
  // the geometric controller (kind "se3")
  a.Vector({"se3_position_gain", "1/s^2", "se3: on the position error"}, &se3.position_gain, 0,
           1e5);
  a.Vector({"se3_velocity_gain", "1/s", "se3: on the velocity error"}, &se3.velocity_gain, 0, 1e5);
  a.Vector({"se3_attitude_gain", "1/s^2", "se3: on the attitude error"}, &se3.attitude_gain, 0,
           1e5);
  a.Vector({"se3_rate_gain", "1/s", "se3: on the body-rate error"}, &se3.rate_gain, 0, 1e5);
  a.Vector({"se3_position_integral", "1/s^3",
            "se3: on the position error's integral, below position times velocity gain (a "
            "scenario with wind: 12, none with the observer)"},
           &se3.position_integral, 0, 1e5);
  a.Number({"se3_integral_limit", "m/s^2", "se3: the integral term's anti-windup clamp"},
           &se3.integral_limit, 0, 100);
  observer.Describe(a);
  // the attitude and rate loops below any command that needs them
  a.Vector({"attitude_gain", "1/s", "rate per radian of error: roll, pitch, yaw"},
           &inner.attitude.gain, 0, 1e5);
  a.Vector({"max_rate", "rad/s", "the body-rate setpoint's limits"}, &inner.attitude.max_rate, 0,
           1e5);
  a.Number({"yaw_weight", "", "the yaw's share of the attitude error (reduced-attitude control)"},
           &inner.attitude.yaw_weight, 0.01, 1);
  a.Vector({"rate_gain", "1/s", "angular acceleration per rad/s of error"}, &inner.rate.gain, 0,
           1e5);
  a.Vector({"rate_integral", "1/s^2", "the rate error's integral"}, &inner.rate.integral, 0, 1e5);
  a.Vector({"rate_derivative", "", "on the measured rate"}, &inner.rate.derivative, 0, 1e5);
  a.Vector({"rate_integral_limit", "rad/s^2", "the integral term's anti-windup clamp"},
           &inner.rate.integral_limit, 0, 1e5);
}

void ControllerConfig::Validate() const {
  ValidateFields(*this, "controller");
  cascade.Validate();
  se3.Validate();
  inner.Validate();
  if (kind == "indi") params.GetOr<IndiParams>().Validate(rate);
  if (kind == "indi" && observer.enabled) {
    throw std::invalid_argument(
        "controller.observer: indi measures the external force itself (the observer would count "
        "it twice); the observer is for the other kinds");
  }
}

bool MeasuresAcceleration(const ControllerConfig& config) {
  return config.kind == "indi" || config.observer.enabled;
}

Registry<ControllerFactory>& Controllers() {
  static Registry<ControllerFactory> registry = [] {
    Registry<ControllerFactory> r;
    r.Register("cascade", [](const ControllerConfig& config, const QuadParams& vehicle) {
      return std::make_unique<CascadeController>(config.cascade, 1.0 / config.rate, vehicle.mass);
    });
    r.Register("se3", [](const ControllerConfig& config, const QuadParams& vehicle) {
      Se3Params se3 = config.se3;
      // the observer meets a steady force itself: an integral too would only add a slow mode
      if (config.observer.enabled) se3.position_integral = Vec3::Zero();
      return std::make_unique<Se3Controller>(se3, vehicle);
    });
    r.Register(
        "indi",
        [](const ControllerConfig& config, const QuadParams& vehicle) {
          IndiParams indi = config.params.GetOr<IndiParams>();
          indi.gains.max_tilt = config.cascade.max_tilt;
          return std::make_unique<IndiController>(indi, vehicle, config.rate);
        },
        PluginParameters::Of(IndiParams()));
    return r;
  }();
  return registry;
}

namespace {

class DragFeedForward : public Controller {
 public:
  DragFeedForward(std::unique_ptr<Controller> inner, const DragModel& drag)
      : inner_(std::move(inner)), drag_(drag) {}
  void Sense(const Surroundings& now) override { inner_->Sense(now); }
  ControlStatus Update(double t, const State& state, const FlatOutput& setpoint,
                       ControlCommand* command) override {
    return inner_->Update(t, state, CompensateDrag(setpoint, drag_), command);
  }
  std::vector<std::string> ReportColumns() const override { return inner_->ReportColumns(); }
  void Report(std::vector<double>* values) const override { inner_->Report(values); }

 private:
  std::unique_ptr<Controller> inner_;
  DragModel drag_;
};

}  // namespace

std::unique_ptr<Controller> WithDragFeedForward(std::unique_ptr<Controller> inner,
                                                const DragModel& drag) {
  return std::make_unique<DragFeedForward>(std::move(inner), drag);
}

std::unique_ptr<Controller> MakeController(const ControllerConfig& config,
                                           const QuadParams& vehicle) {
  const ControllerFactory* factory = Controllers().Find(config.kind);
  if (factory == nullptr) {
    throw std::invalid_argument("unknown controller '" + config.kind + "' (expected " +
                                Controllers().NameList() + ")");
  }
  ControllerConfig filled = config;
  if (filled.params.empty()) filled.params = Controllers().Parameters(config.kind);
  std::unique_ptr<Controller> controller = (*factory)(filled, vehicle);
  if (config.observer.enabled) {
    return WithDisturbanceObserver(std::move(controller), config.observer, vehicle.mass,
                                   1.0 / config.rate);
  }
  // a controller that measures the force measures the drag with it: fed forward too, it would
  // count twice
  if (!config.drag_feedforward || MeasuresAcceleration(config)) return controller;
  return WithDragFeedForward(std::move(controller), LumpedDrag(vehicle));
}

}  // namespace aerobox
