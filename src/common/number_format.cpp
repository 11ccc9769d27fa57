#include "common/number_format.h"

#include <charconv>
#include <system_error>

namespace aerobox {

void AppendNumber(double value, std::string* text) {
  if (value == 0.0) value = 0.0;  // folds -0 into 0
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  text->append(buffer, result.ptr);
}

std::string FormatNumber(double value) {
  std::string text;
  AppendNumber(value, &text);
  return text;
}

std::string FormatVector(const Eigen::Ref<const Eigen::VectorXd>& values,
                         std::string_view separator) {
  std::string text;
  AppendVector(values, separator, &text);
  return text;
}

void AppendVector(const Eigen::Ref<const Eigen::VectorXd>& values, std::string_view separator,
                  std::string* text) {
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    if (i > 0) text->append(separator);
    AppendNumber(values[i], text);
  }
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
