#include "common/rates.h"

#include <cmath>
#include <stdexcept>

#include "common/number_format.h"

namespace aerobox {

int StepsPerPeriod(double rate, double step, const std::string& what) {
  const double steps = 1.0 / (rate * step);
  const long rounded = std::lround(steps);
  if (!(rate > 0) || rounded < 1 || std::abs(steps - static_cast<double>(rounded)) > 1e-6) {
    throw std::invalid_argument(what + " " + FormatNumber(rate) +
                                " Hz must divide the physics rate " + FormatNumber(1.0 / step) +
                                " Hz");
  }
  return static_cast<int>(rounded);
}

}  // namespace aerobox
