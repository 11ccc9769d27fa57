// A flat-to-nested JSON object writer for summaries: keys in insertion order, numbers in their
// shortest round-trip form, strings escaped. Enough for summary.json; not a general JSON library.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace aerobox {

class JsonObject {
 public:
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

  // Pretty-printed with two-space indentation and a final newline at the top level.
  std::string Text(int indent = 0) const;

 private:
  // key and encoded value; a nested object's value is "\x01<index into children_>"
  std::vector<std::pair<std::string, std::string>> members_;
  std::vector<JsonObject> children_;
};

}  // namespace aerobox
