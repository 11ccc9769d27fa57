// The JSON summaries aerobox writes (summary.json): an object whose keys keep their insertion
// order, written by nlohmann-json (its types stay in the .cpp). Numbers are written in their
// shortest round-trip form; a non-finite number becomes null, as JSON has no infinity.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace aerobox {

class JsonObject {
 public:
  JsonObject();
  ~JsonObject();
  JsonObject(const JsonObject& other);
  JsonObject& operator=(const JsonObject& other);

  // Adding a key again replaces its value, keeping its place.
  JsonObject& Add(const std::string& key, double value);
  JsonObject& Add(const std::string& key, long long value);
  JsonObject& Add(const std::string& key, int value) {
    return Add(key, static_cast<long long>(value));
  }
  JsonObject& Add(const std::string& key, bool value);
  JsonObject& Add(const std::string& key, const std::string& value);
  JsonObject& Add(const std::string& key, const char* value) {
    return Add(key, std::string(value));
  }
  JsonObject& Add(const std::string& key, const JsonObject& value);
  // An array of numbers (e.g. a point [x, y, z]); non-finite entries become null.
  JsonObject& Add(const std::string& key, const std::vector<double>& values);
  // An array of objects.
  JsonObject& Add(const std::string& key, const std::vector<JsonObject>& values);

  // Pretty-printed with two-space indentation and a final newline.
  std::string Text() const;

 private:
  struct Value;  // nlohmann::ordered_json
  std::unique_ptr<Value> value_;
};

}  // namespace aerobox
