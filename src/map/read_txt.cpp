#include <array>

#include "common/number_format.h"
#include "map/map_reader.h"
#include "map/text_fields.h"

namespace aerobox {
namespace {

using map_detail::ParseFiniteField;

constexpr std::array<const char*, 9> kFieldNames = {"xmin", "ymin", "zmin", "xmax", "ymax",
                                                    "zmax", "r",    "g",    "b"};

// The numbers after the keyword: 6 extents, optionally followed by 3 colour components.
std::vector<double> ParseNumbers(const std::vector<std::string_view>& fields,
                                 const SourceLocation& where, const std::string& keyword) {
  const size_t count = fields.size() - 1;
  if (count != 6 && count != 9) {
    throw InputError(where, keyword,
                     "expected 6 numbers (xmin ymin zmin xmax ymax zmax) or 9 (with r g b), "
                     "found " +
                         std::to_string(count));
  }
  std::vector<double> numbers;
  for (size_t i = 0; i < count; ++i) {
    numbers.push_back(ParseFiniteField(fields[i + 1], where, keyword + " " + kFieldNames[i]));
  }
  return numbers;
}

}  // namespace

Map ReadTxtMap(std::istream& in, const std::string& file) {
  const std::string text = map_detail::ReadAll(in, file);
  Map map;
  map.source = file;
  for (const map_detail::Line& line : map_detail::SplitLines(text)) {
    const std::string_view content = map_detail::StripComment(line.text);
    if (content.empty()) continue;
    const auto fields = map_detail::SplitFields(content, " \t\v\f");
    const std::string keyword(fields[0].substr(0, 40));
    const SourceLocation where{file, line.number};
    if (keyword == "boundary") {
      if (map.bounds_line != 0) {
        throw InputError(where, keyword,
                         "given twice (first at line " + std::to_string(map.bounds_line) + ")");
      }
      const std::vector<double> n = ParseNumbers(fields, where, keyword);
      map.bounds = {Vec3(n[0], n[1], n[2]), Vec3(n[3], n[4], n[5])};
      map.bounds_line = line.number;
    } else if (keyword == "block") {
      const std::vector<double> n = ParseNumbers(fields, where, keyword);
      Box box;
      box.extent = {Vec3(n[0], n[1], n[2]), Vec3(n[3], n[4], n[5])};
      if (n.size() == 9) {
        box.rgb = map_detail::NormalizeColour(Vec3(n[6], n[7], n[8]), where, keyword);
      }
      box.name = "block_" + std::to_string(map.boxes.size());
      box.line = line.number;
      map.boxes.push_back(box);
    } else {
      throw InputError(where, "keyword",
                       "unknown keyword '" + keyword + "' (expected 'boundary' or 'block')");
    }
  }
  if (text.find_first_not_of(" \t\r\n\v\f") == std::string::npos) {
    throw InputError({file, 1}, "", "the map is empty");
  }
  if (map.bounds_line == 0)
    throw InputError({file, 1}, "boundary", "no 'boundary' line in the file");
  return map;
}

}  // namespace aerobox
