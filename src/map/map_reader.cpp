#include "map/map_reader.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <sstream>

#include "map/read_file.h"
#include "map/text_fields.h"

namespace aerobox {
namespace {

std::string Lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

}  // namespace

MapFormat DetectMapFormat(std::string_view file_name, std::string_view head) {
  const std::string extension = Lower(std::filesystem::path(file_name).extension().string());
  if (extension == ".json") return MapFormat::kJson;
  if (extension == ".csv") return MapFormat::kCsv;
  if (extension == ".txt") return MapFormat::kTxt;
  const size_t first = head.find_first_not_of(" \t\r\n\xEF\xBB\xBF");
  if (first == std::string_view::npos) return MapFormat::kTxt;
  if (head[first] == '{') return MapFormat::kJson;
  if (head.substr(first, 4) == "lat0") return MapFormat::kCsv;
  return MapFormat::kTxt;
}

Map ReadMap(std::istream& in, const std::string& file, MapFormat format) {
  Map map;
  switch (format) {
    case MapFormat::kTxt:
      map = ReadTxtMap(in, file);
      break;
    case MapFormat::kJson:
      map = ReadJsonMap(in, file);
      break;
    case MapFormat::kCsv:
      map = ReadCsvMap(in, file);
      break;
  }
  map.name = std::filesystem::path(file).stem().string();
  ValidateMap(map);
  return map;
}

StartGoal ReadStartGoal(std::istream& in, const std::string& file) {
  const std::string text = map_detail::ReadAll(in, file);
  std::optional<Vec3> start;
  std::optional<Vec3> goal;
  for (const map_detail::Line& line : map_detail::SplitLines(text)) {
    const std::string_view content = map_detail::StripComment(line.text);
    if (content.empty()) continue;
    const SourceLocation where{file, line.number};
    const size_t colon = content.find(':');
    const std::string key(map_detail::StripComment(content.substr(0, colon)).substr(0, 40));
    if (colon == std::string_view::npos || (key != "start" && key != "goal")) {
      throw InputError(where, "key", "expected 'start: (x, y, z)' or 'goal: (x, y, z)'");
    }
    const auto fields = map_detail::SplitFields(content.substr(colon + 1), " \t,()");
    if (fields.size() != 3) {
      throw InputError(where, key, "expected 3 numbers, found " + std::to_string(fields.size()));
    }
    Vec3 point;
    for (int i = 0; i < 3; ++i) {
      point[i] =
          map_detail::ParseFiniteField(fields[i], where, key + "[" + std::to_string(i) + "]");
    }
    std::optional<Vec3>& slot = key == "start" ? start : goal;
    if (slot) throw InputError(where, key, "given twice");
    slot = point;
  }
  if (!start) throw InputError({file, 0}, "start", "no 'start:' line");
  if (!goal) throw InputError({file, 0}, "goal", "no 'goal:' line");
  return {*start, *goal};
}

Map ReadMapFile(const std::string& path) {
  const std::string text = ReadTextFile(path);
  std::istringstream in(text);
  return ReadMap(in, path, DetectMapFormat(path, text.substr(0, 64)));
}

}  // namespace aerobox
