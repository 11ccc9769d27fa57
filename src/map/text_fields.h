// Line and field helpers shared by the text map readers (internal to src/map).
#pragma once

#include <istream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/error.h"
#include "common/types.h"

namespace aerobox::map_detail {

// Largest map file we read [bytes]; the 3845-building city is 0.2 MB.
inline constexpr size_t kMaxFileBytes = 64u << 20;

// The whole stream as text, without a UTF-8 byte-order mark. Throws InputError when it is
// larger than kMaxFileBytes or cannot be read.
std::string ReadAll(std::istream& in, const std::string& file);

// One line of a file, 1-based, without its "\n", "\r\n" or "\r" ending.
struct Line {
  int number = 0;
  std::string_view text;
};
std::vector<Line> SplitLines(std::string_view text);

// The line with a '#' comment and surrounding white space removed.
std::string_view StripComment(std::string_view line);

// Non-empty pieces of `text` between any of the `separators`.
std::vector<std::string_view> SplitFields(std::string_view text, std::string_view separators);

// The token as a finite number; otherwise throws InputError naming `field` and the token.
double ParseFiniteField(std::string_view token, const SourceLocation& where,
                        const std::string& field);

// A colour written either as 0-255 (any component above 1) or as 0-1, as the map formats do,
// mapped to [0, 1]. Throws InputError for negative or above-255 components.
Vec3 NormalizeColour(const Vec3& raw, const SourceLocation& where, const std::string& field);

// A colour by name, as matplotlib takes them (flightsim's worlds use them): the base colours
// ("b", "g", "r", "c", "m", "y", "k", "w"), the Tableau ones ("tab:blue", ...), the common
// CSS/X11 names ("blue", "orange", "gray", ...) in any case, and "#rrggbb". RGB in [0, 1].
std::optional<Vec3> NamedColour(const std::string& name);

}  // namespace aerobox::map_detail
