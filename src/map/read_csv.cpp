#include <array>

#include "map/map_reader.h"
#include "map/text_fields.h"

namespace aerobox {
namespace {

constexpr std::array<const char*, 6> kColumns = {"posX",      "posY",      "posZ",
                                                 "halfSizeX", "halfSizeY", "halfSizeZ"};
// Buildings carry no colour in the CSV: a light concrete grey.
const Vec3 kBuildingRgb(0.72, 0.72, 0.70);

// Line 1: "lat0 37.792480, lon0 -122.397450" (the geodetic origin; checked, then not used).
void CheckOriginLine(const map_detail::Line& line, const std::string& file) {
  const auto fields = map_detail::SplitFields(line.text, " ,\t");
  if (fields.size() != 4 || fields[0] != "lat0" || fields[2] != "lon0") {
    throw InputError({file, line.number}, "origin",
                     "expected 'lat0 <degrees>, lon0 <degrees>' on the first line");
  }
  map_detail::ParseFiniteField(fields[1], {file, line.number}, "lat0");
  map_detail::ParseFiniteField(fields[3], {file, line.number}, "lon0");
}

void CheckHeaderLine(const map_detail::Line& line, const std::string& file) {
  const auto fields = map_detail::SplitFields(line.text, ", \t");
  bool matches = fields.size() == kColumns.size();
  for (size_t i = 0; matches && i < kColumns.size(); ++i) matches = fields[i] == kColumns[i];
  if (!matches) {
    throw InputError({file, line.number}, "header",
                     "expected 'posX,posY,posZ,halfSizeX,halfSizeY,halfSizeZ' on the second line");
  }
}

}  // namespace

Map ReadCsvMap(std::istream& in, const std::string& file) {
  const std::string text = map_detail::ReadAll(in, file);
  const std::vector<map_detail::Line> lines = map_detail::SplitLines(text);
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) {
    throw InputError({file, 1}, "", "the map is empty");
  }
  CheckOriginLine(lines[0], file);
  if (lines.size() < 2) throw InputError({file, 1}, "header", "the column header is missing");
  CheckHeaderLine(lines[1], file);

  Map map;
  map.source = file;
  for (size_t i = 2; i < lines.size(); ++i) {
    const SourceLocation where{file, lines[i].number};
    const auto fields = map_detail::SplitFields(lines[i].text, ",");
    if (fields.empty() || (fields.size() == 1 && map_detail::StripComment(fields[0]).empty())) {
      continue;  // blank line
    }
    if (fields.size() != kColumns.size()) {
      throw InputError(
          where, "row",
          "expected 6 comma-separated numbers, found " + std::to_string(fields.size()) + " fields");
    }
    double n[kColumns.size()];
    for (size_t c = 0; c < kColumns.size(); ++c) {
      const std::string_view field = map_detail::StripComment(fields[c]);
      n[c] = map_detail::ParseFiniteField(field, where, kColumns[c]);
    }
    const Vec3 centre(n[0], n[1], n[2]);
    const Vec3 half(n[3], n[4], n[5]);
    for (int axis = 0; axis < 3; ++axis) {
      if (!(half[axis] > 0.0)) {
        throw InputError(where, kColumns[3 + axis], "half-size must be positive");
      }
    }
    Box box;
    box.extent = {centre - half, centre + half};
    box.rgb = kBuildingRgb;
    box.name = "block_" + std::to_string(map.boxes.size());
    box.line = lines[i].number;
    map.boxes.push_back(box);
  }
  if (map.boxes.empty()) throw InputError({file, 0}, "rows", "the map has no buildings");

  map.bounds = map.boxes.front().extent;
  for (const Box& box : map.boxes) {
    map.bounds.min = map.bounds.min.cwiseMin(box.extent.min);
    map.bounds.max = map.bounds.max.cwiseMax(box.extent.max);
  }
  return map;
}

}  // namespace aerobox
