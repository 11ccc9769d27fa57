#include "telemetry/json_object.h"

#include <cmath>

#include "common/number_format.h"

namespace aerobox {
namespace {

std::string Quote(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buffer[8];
          std::snprintf(buffer, sizeof(buffer), "\\u%04x", c);
          out += buffer;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

}  // namespace

JsonObject& JsonObject::Add(const std::string& key, double value) {
  // JSON has no infinity or NaN: null says "none"
  members_.emplace_back(key, std::isfinite(value) ? FormatNumber(value) : "null");
  return *this;
}

JsonObject& JsonObject::Add(const std::string& key, long long value) {
  members_.emplace_back(key, std::to_string(value));
  return *this;
}

JsonObject& JsonObject::Add(const std::string& key, bool value) {
  members_.emplace_back(key, value ? "true" : "false");
  return *this;
}

JsonObject& JsonObject::Add(const std::string& key, const std::string& value) {
  members_.emplace_back(key, Quote(value));
  return *this;
}

JsonObject& JsonObject::Add(const std::string& key, const JsonObject& value) {
  members_.emplace_back(key, "\x01" + std::to_string(children_.size()));
  children_.push_back(value);
  return *this;
}

std::string JsonObject::Text(int indent) const {
  const std::string pad(2 * (indent + 1), ' ');
  std::string out = "{\n";
  for (size_t i = 0; i < members_.size(); ++i) {
    const auto& [key, value] = members_[i];
    out += pad + Quote(key) + ": ";
    out += value.rfind('\x01', 0) == 0 ? children_[std::stoul(value.substr(1))].Text(indent + 1)
                                       : value;
    out += i + 1 < members_.size() ? ",\n" : "\n";
  }
  out += std::string(2 * indent, ' ') + "}";
  if (indent == 0) out += "\n";
  return out;
}

}  // namespace aerobox
