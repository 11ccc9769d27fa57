#include "control/disturbance_observer.h"

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace aerobox {

void DisturbanceObserverParams::Describe(Archive& a) {
  a.Boolean({"observer", "",
             "estimate the external force from the measured acceleration and the rotors' thrust, "
             "and feed it forward (any kind; it replaces drag_feedforward)"},
            &enabled);
  a.Number({"observer_time_constant", "s", "the estimate's first-order filter"}, &time_constant,
           1e-3, 10);
}

DisturbanceObserver::DisturbanceObserver(double time_constant, double mass)
    : time_constant_(time_constant), mass_(mass) {}

void DisturbanceObserver::Update(double dt, const Surroundings& now, const Quat& q_WB) {
  const Vec3 thrust_W = q_WB.normalized() * Vec3(0, 0, now.rotor_thrusts.sum());
  const Vec3 raw = ExternalForce(mass_, now.acceleration_W, thrust_W);
  if (!raw.allFinite()) return;
  const double blend = started_ ? 1.0 - std::exp(-dt / time_constant_) : 1.0;
  force_W_ += blend * (raw - force_W_);
  started_ = true;
}

namespace {

class ObservedController : public Controller {
 public:
  ObservedController(std::unique_ptr<Controller> inner, const DisturbanceObserverParams& params,
                     double mass, double period)
      : inner_(std::move(inner)),
        observer_(params.time_constant, mass),
        mass_(mass),
        period_(period) {}

  void Sense(const Surroundings& now) override {
    now_ = now;
    inner_->Sense(now);
  }
  ControlStatus Update(double t, const State& state, const FlatOutput& setpoint,
                       ControlCommand* command) override {
    observer_.Update(period_, now_, state.q_WB);
    FlatOutput fed = setpoint;
    fed.a_W -= observer_.force_W() / mass_;
    return inner_->Update(t, state, fed, command);
  }
  std::vector<std::string> ReportColumns() const override {
    std::vector<std::string> columns = inner_->ReportColumns();
    columns.insert(columns.end(), {"fext_x", "fext_y", "fext_z"});
    return columns;
  }
  void Report(std::vector<double>* values) const override {
    inner_->Report(values);
    const Vec3& f = observer_.force_W();
    values->insert(values->end(), {f.x(), f.y(), f.z()});
  }

 private:
  std::unique_ptr<Controller> inner_;
  DisturbanceObserver observer_;
  double mass_, period_;
  Surroundings now_;
};

}  // namespace

std::unique_ptr<Controller> WithDisturbanceObserver(std::unique_ptr<Controller> inner,
                                                    const DisturbanceObserverParams& params,
                                                    double mass, double period) {
  return std::make_unique<ObservedController>(std::move(inner), params, mass, period);
}

}  // namespace aerobox
