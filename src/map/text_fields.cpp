#include "map/text_fields.h"

#include <cmath>
#include <iterator>

#include "common/number_format.h"

namespace aerobox::map_detail {

std::string ReadAll(std::istream& in, const std::string& file) {
  std::string text;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof(buffer)) || in.gcount() > 0) {
    text.append(buffer, static_cast<size_t>(in.gcount()));
    if (text.size() > kMaxFileBytes) {
      throw InputError({file, 0}, "", "file is larger than the 64 MiB a map may have");
    }
  }
  if (in.bad()) throw InputError({file, 0}, "", "could not be read");
  constexpr std::string_view kBom = "\xEF\xBB\xBF";
  if (std::string_view(text).substr(0, kBom.size()) == kBom) text.erase(0, kBom.size());
  return text;
}

std::vector<Line> SplitLines(std::string_view text) {
  std::vector<Line> lines;
  int number = 1;
  size_t begin = 0;
  while (begin < text.size()) {
    size_t end = text.find_first_of("\r\n", begin);
    if (end == std::string_view::npos) end = text.size();
    lines.push_back({number++, text.substr(begin, end - begin)});
    // "\r\n" is one line ending, a lone "\r" or "\n" is one too
    if (end < text.size() && text[end] == '\r' && end + 1 < text.size() && text[end + 1] == '\n') {
      ++end;
    }
    begin = end + 1;
  }
  return lines;
}

std::string_view StripComment(std::string_view line) {
  line = line.substr(0, line.find('#'));
  constexpr std::string_view kSpace = " \t\v\f";
  const size_t first = line.find_first_not_of(kSpace);
  if (first == std::string_view::npos) return {};
  const size_t last = line.find_last_not_of(kSpace);
  return line.substr(first, last - first + 1);
}

std::vector<std::string_view> SplitFields(std::string_view text, std::string_view separators) {
  std::vector<std::string_view> fields;
  size_t begin = text.find_first_not_of(separators);
  while (begin != std::string_view::npos) {
    size_t end = text.find_first_of(separators, begin);
    if (end == std::string_view::npos) end = text.size();
    fields.push_back(text.substr(begin, end - begin));
    begin = text.find_first_not_of(separators, end);
  }
  return fields;
}

double ParseFiniteField(std::string_view token, const SourceLocation& where,
                        const std::string& field) {
  double value = 0.0;
  // quote at most 40 characters of a bad token: binary junk should not flood the terminal
  const std::string shown(token.substr(0, 40));
  if (!ParseNumber(token, &value)) {
    throw InputError(where, field, "'" + shown + "' is not a number");
  }
  if (!std::isfinite(value)) {
    throw InputError(where, field, "'" + shown + "' is not a finite number");
  }
  return value;
}

Vec3 NormalizeColour(const Vec3& raw, const SourceLocation& where, const std::string& field) {
  if ((raw.array() < 0.0).any() || (raw.array() > 255.0).any()) {
    throw InputError(where, field, "colour " + FormatVector(raw) + " is outside 0-255 (or 0-1)");
  }
  return (raw.array() > 1.0).any() ? Vec3(raw / 255.0) : raw;
}

}  // namespace aerobox::map_detail
