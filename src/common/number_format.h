// Locale-independent number text: the shortest form that reads back to the same double.
#pragma once

#include <string>
#include <string_view>

#include "common/types.h"

namespace aerobox {

// Shortest round-trip text of `value` ("0.1", "2", "1e-05"); -0 is written as 0.
std::string FormatNumber(double value);
// The same, appended to `text` (no temporary string: telemetry writes 10^4 numbers a second).
void AppendNumber(double value, std::string* text);

// The components separated by `separator`, e.g. "1 2.5 0" or "1,2.5,0".
std::string FormatVector(const Eigen::Ref<const Eigen::VectorXd>& values,
                         std::string_view separator = " ");
void AppendVector(const Eigen::Ref<const Eigen::VectorXd>& values, std::string_view separator,
                  std::string* text);

// Parses a whole token as a finite or infinite double in the C locale. Accepts a leading '+'.
// Returns false when the token is not a number (trailing text, empty, ...).
bool ParseNumber(std::string_view token, double* value);

}  // namespace aerobox
