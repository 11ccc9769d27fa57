#include "common/fault_injection.h"

#include <cstdlib>

namespace aerobox {

std::optional<std::string> InjectedFault(std::string_view kind) {
  const char* variable = std::getenv("AEROBOX_FAULT");
  if (variable == nullptr) return std::nullopt;
  std::string_view faults(variable);
  while (!faults.empty()) {
    const size_t comma = faults.find(',');
    const std::string_view fault = faults.substr(0, comma);
    faults = comma == std::string_view::npos ? std::string_view() : faults.substr(comma + 1);
    const size_t colon = fault.find(':');
    if (fault.substr(0, colon) != kind) continue;
    return colon == std::string_view::npos ? std::string() : std::string(fault.substr(colon + 1));
  }
  return std::nullopt;
}

}  // namespace aerobox
