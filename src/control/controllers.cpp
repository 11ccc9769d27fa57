#include "control/controllers.h"

#include <cmath>
#include <stdexcept>

#include "common/drag.h"
#include "common/number_format.h"
#include "control/cascade.h"

namespace aerobox {

void ControllerConfig::Validate() const {
  if (!(rate > 0 && rate <= 1000.0 && std::isfinite(rate))) {
    throw std::invalid_argument("ControllerConfig.rate must be in (0, 1000] Hz, got " +
                                FormatNumber(rate));
  }
  cascade.Validate();
  se3.Validate();
  inner.Validate();
}

Registry<ControllerFactory>& Controllers() {
  static Registry<ControllerFactory> registry = [] {
    Registry<ControllerFactory> r;
    r.Register("cascade", [](const ControllerConfig& config, const QuadParams& vehicle) {
      return std::make_unique<CascadeController>(config.cascade, 1.0 / config.rate, vehicle.mass);
    });
    r.Register("se3", [](const ControllerConfig& config, const QuadParams& vehicle) {
      return std::make_unique<Se3Controller>(config.se3, vehicle);
    });
    return r;
  }();
  return registry;
}

namespace {

class DragFeedForward : public Controller {
 public:
  DragFeedForward(std::unique_ptr<Controller> inner, const DragModel& drag)
      : inner_(std::move(inner)), drag_(drag) {}
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
  if (!config.drag_feedforward) return controller;
  return WithDragFeedForward(std::move(controller), LumpedDrag(vehicle));
}

}  // namespace aerobox
