#include "control/controllers.h"

#include <cmath>
#include <stdexcept>

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

std::unique_ptr<Controller> MakeController(const ControllerConfig& config,
                                           const QuadParams& vehicle) {
  const ControllerFactory* factory = Controllers().Find(config.kind);
  if (factory == nullptr) {
    throw std::invalid_argument("unknown controller '" + config.kind + "' (expected " +
                                Controllers().NameList() + ")");
  }
  return (*factory)(config, vehicle);
}

}  // namespace aerobox
