#include "common/number_format.h"

#include <charconv>
#include <system_error>

namespace aerobox {

std::string FormatNumber(double value) {
  if (value == 0.0) value = 0.0;  // folds -0 into 0
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

std::string FormatVector(const Eigen::Ref<const Eigen::VectorXd>& values,
                         std::string_view separator) {
  std::string text;
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    if (i > 0) text += separator;
    text += FormatNumber(values[i]);
  }
  return text;
}

bool ParseNumber(std::string_view token, double* value) {
  // from_chars takes no leading '+': allow one, but not in front of another sign
  if (!token.empty() && token.front() == '+') {
    token.remove_prefix(1);
    if (!token.empty() && (token.front() == '+' || token.front() == '-')) return false;
  }
  if (token.empty()) return false;
  const char* end = token.data() + token.size();
  const auto result = std::from_chars(token.data(), end, *value);
  return result.ec == std::errc() && result.ptr == end;
}

}  // namespace aerobox
