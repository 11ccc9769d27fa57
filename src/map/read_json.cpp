#include <cmath>
#include <initializer_list>

#include "map/json_document.h"
#include "map/map_reader.h"
#include "map/text_fields.h"

namespace aerobox {
namespace {

using map_detail::JsonValue;

// The numbers of an array of exactly `count` finite numbers; otherwise InputError at its line.
std::vector<double> FiniteNumbers(const JsonValue& value, size_t count, const std::string& file,
                                  const std::string& field) {
  const SourceLocation where{file, value.line};
  if (value.kind != JsonValue::Kind::kArray) {
    throw InputError(where, field,
                     std::string("expected an array of ") + std::to_string(count) +
                         " numbers, found " + map_detail::KindName(value.kind));
  }
  if (value.items.size() != count) {
    throw InputError(where, field,
                     "expected " + std::to_string(count) + " numbers, found " +
                         std::to_string(value.items.size()));
  }
  std::vector<double> numbers;
  for (size_t i = 0; i < count; ++i) {
    const JsonValue& item = value.items[i];
    const std::string item_field = field + "[" + std::to_string(i) + "]";
    if (item.kind != JsonValue::Kind::kNumber) {
      throw InputError({file, item.line}, item_field,
                       std::string("expected a number, found ") + map_detail::KindName(item.kind));
    }
    if (!std::isfinite(item.number)) {
      throw InputError({file, item.line}, item_field, "must be a finite number");
    }
    numbers.push_back(item.number);
  }
  return numbers;
}

// Interleaved [xmin, xmax, ymin, ymax, zmin, zmax], as flightsim writes extents.
Aabb InterleavedExtents(const JsonValue& value, const std::string& file, const std::string& field) {
  const std::vector<double> n = FiniteNumbers(value, 6, file, field);
  return {Vec3(n[0], n[2], n[4]), Vec3(n[1], n[3], n[5])};
}

const JsonValue& Require(const JsonValue& object, const char* key, const std::string& file,
                         const std::string& field) {
  const JsonValue* member = object.Find(key);
  if (member == nullptr) {
    throw InputError({file, object.line}, field, std::string("missing key \"") + key + "\"");
  }
  return *member;
}

void RequireObject(const JsonValue& value, const std::string& file, const std::string& field) {
  if (value.kind != JsonValue::Kind::kObject) {
    throw InputError({file, value.line}, field,
                     std::string("expected an object, found ") + map_detail::KindName(value.kind));
  }
}

// Keys other than `known` are errors: a misspelt key would otherwise be ignored in silence.
void RejectUnknownKeys(const JsonValue& object, std::initializer_list<const char*> known,
                       const std::string& file, const std::string& field) {
  for (const auto& [key, value] : object.members) {
    bool found = false;
    for (const char* k : known) found = found || key == k;
    if (found) continue;
    std::string expected;
    for (const char* k : known) expected += (expected.empty() ? "" : ", ") + std::string(k);
    throw InputError({file, value.line}, field.empty() ? key : field + "." + key,
                     "unknown key (expected " + expected + ")");
  }
}

}  // namespace

Map ReadJsonMap(std::istream& in, const std::string& file) {
  const std::string text = map_detail::ReadAll(in, file);
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) {
    throw InputError({file, 1}, "", "the map is empty");
  }
  const JsonValue root = map_detail::ParseJson(text, file);
  RequireObject(root, file, "document");
  // flightsim's own keys besides the map (margin, resolution, ...) are accepted and ignored
  RejectUnknownKeys(root,
                    {"bounds", "blocks", "start", "goal", "margin", "resolution", "timeout",
                     "expected_path_length", "algorithms"},
                    file, "");

  Map map;
  map.source = file;
  const JsonValue& bounds = Require(root, "bounds", file, "document");
  RequireObject(bounds, file, "bounds");
  const JsonValue& bounds_extents = Require(bounds, "extents", file, "bounds");
  map.bounds = InterleavedExtents(bounds_extents, file, "bounds.extents");
  map.bounds_line = bounds_extents.line;

  if (const JsonValue* blocks = root.Find("blocks")) {
    if (blocks->kind != JsonValue::Kind::kArray) {
      throw InputError(
          {file, blocks->line}, "blocks",
          std::string("expected an array, found ") + map_detail::KindName(blocks->kind));
    }
    for (const JsonValue& block : blocks->items) {
      const std::string field = "blocks[" + std::to_string(map.boxes.size()) + "]";
      RequireObject(block, file, field);
      RejectUnknownKeys(block, {"extents", "color"}, file, field);
      Box box;
      box.extent =
          InterleavedExtents(Require(block, "extents", file, field), file, field + ".extents");
      if (const JsonValue* color = block.Find("color")) {
        if (color->kind == JsonValue::Kind::kString) {
          // flightsim draws with matplotlib, which takes colour names
          const std::optional<Vec3> named = map_detail::NamedColour(color->text);
          if (!named) {
            throw InputError(
                {file, color->line}, field + ".color",
                "unknown colour name \"" + color->text +
                    "\" (expected a matplotlib or CSS name, \"#rrggbb\" or [r, g, b])");
          }
          box.rgb = *named;
        } else {
          const std::vector<double> c = FiniteNumbers(*color, 3, file, field + ".color");
          box.rgb = map_detail::NormalizeColour(Vec3(c[0], c[1], c[2]), {file, color->line},
                                                field + ".color");
        }
      }
      box.name = "block_" + std::to_string(map.boxes.size());
      box.line = block.line;
      map.boxes.push_back(box);
    }
  }
  for (const char* key : {"start", "goal"}) {
    if (const JsonValue* point = root.Find(key)) {
      const std::vector<double> p = FiniteNumbers(*point, 3, file, key);
      (std::string_view(key) == "start" ? map.start : map.goal) = Vec3(p[0], p[1], p[2]);
      map.start_goal_line = point->line;
    }
  }
  return map;
}

}  // namespace aerobox
