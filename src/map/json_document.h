// A small JSON reader that remembers the line of every value, so that a map error can name it.
// Internal to src/map. Accepts standard JSON plus the tokens Infinity, -Infinity and NaN, which
// published maps contain (flightsim's test_impossible.json).
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/error.h"

namespace aerobox::map_detail {

struct JsonValue {
  enum class Kind { kNull, kBool, kNumber, kString, kArray, kObject };

  Kind kind = Kind::kNull;
  int line = 0;                  // 1-based line where the value starts
  bool boolean = false;          // kBool
  double number = 0.0;           // kNumber (may be +-inf or NaN from the extra tokens)
  std::string text;              // kString
  std::vector<JsonValue> items;  // kArray
  std::vector<std::pair<std::string, JsonValue>> members;  // kObject, in file order

  // The member named `key` of an object, or nullptr.
  const JsonValue* Find(std::string_view key) const;
};

// Parses a whole document; throws InputError with the line of the first syntax error.
// Nesting deeper than 64 levels is an error (no input can exhaust the stack).
JsonValue ParseJson(std::string_view text, const std::string& file);

// "an object", "a number", ... for messages.
const char* KindName(JsonValue::Kind kind);

}  // namespace aerobox::map_detail
