#include "map/text_fields.h"

#include <cctype>
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

std::optional<Vec3> NamedColour(const std::string& name) {
  std::string key;
  for (const char c : name) key += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (key.size() == 7 && key[0] == '#') {
    Vec3 rgb;
    for (int i = 0; i < 3; ++i) {
      const std::string hex = key.substr(1 + 2 * i, 2);
      if (hex.find_first_not_of("0123456789abcdef") != std::string::npos) return std::nullopt;
      rgb[i] = std::stoi(hex, nullptr, 16) / 255.0;
    }
    return rgb;
  }
  // hex values of matplotlib's base, Tableau and CSS colours
  static const std::pair<const char*, unsigned> kNames[] = {
      {"b", 0x0000ff},           {"g", 0x008000},         {"r", 0xff0000},
      {"c", 0x00bfbf},           {"m", 0xbf00bf},         {"y", 0xbfbf00},
      {"k", 0x000000},           {"w", 0xffffff},         {"tab:blue", 0x1f77b4},
      {"tab:orange", 0xff7f0e},  {"tab:green", 0x2ca02c}, {"tab:red", 0xd62728},
      {"tab:purple", 0x9467bd},  {"tab:brown", 0x8c564b}, {"tab:pink", 0xe377c2},
      {"tab:gray", 0x7f7f7f},    {"tab:grey", 0x7f7f7f},  {"tab:olive", 0xbcbd22},
      {"tab:cyan", 0x17becf},    {"black", 0x000000},     {"white", 0xffffff},
      {"red", 0xff0000},         {"green", 0x008000},     {"blue", 0x0000ff},
      {"yellow", 0xffff00},      {"cyan", 0x00ffff},      {"aqua", 0x00ffff},
      {"magenta", 0xff00ff},     {"fuchsia", 0xff00ff},   {"gray", 0x808080},
      {"grey", 0x808080},        {"lightgray", 0xd3d3d3}, {"lightgrey", 0xd3d3d3},
      {"darkgray", 0xa9a9a9},    {"darkgrey", 0xa9a9a9},  {"silver", 0xc0c0c0},
      {"orange", 0xffa500},      {"purple", 0x800080},    {"brown", 0xa52a2a},
      {"pink", 0xffc0cb},        {"olive", 0x808000},     {"navy", 0x000080},
      {"teal", 0x008080},        {"maroon", 0x800000},    {"lime", 0x00ff00},
      {"gold", 0xffd700},        {"tan", 0xd2b48c},       {"beige", 0xf5f5dc},
      {"violet", 0xee82ee},      {"indigo", 0x4b0082},    {"turquoise", 0x40e0d0},
      {"salmon", 0xfa8072},      {"coral", 0xff7f50},     {"khaki", 0xf0e68c},
      {"crimson", 0xdc143c},     {"chocolate", 0xd2691e}, {"darkgreen", 0x006400},
      {"darkblue", 0x00008b},    {"darkred", 0x8b0000},   {"lightblue", 0xadd8e6},
      {"lightgreen", 0x90ee90},  {"skyblue", 0x87ceeb},   {"steelblue", 0x4682b4},
      {"forestgreen", 0x228b22}, {"royalblue", 0x4169e1}, {"slategray", 0x708090},
      {"slategrey", 0x708090},
  };
  for (const auto& [colour, hex] : kNames) {
    if (key == colour) {
      return Vec3(((hex >> 16) & 0xff) / 255.0, ((hex >> 8) & 0xff) / 255.0, (hex & 0xff) / 255.0);
    }
  }
  return std::nullopt;
}

}  // namespace aerobox::map_detail
