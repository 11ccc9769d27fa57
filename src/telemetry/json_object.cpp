#include "telemetry/json_object.h"

#include <cmath>
#include <nlohmann/json.hpp>

namespace aerobox {

struct JsonObject::Value {
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
};

namespace {

nlohmann::ordered_json Number(double value) {
  if (!std::isfinite(value)) return nullptr;
  return value;
}

}  // namespace

JsonObject::JsonObject() : value_(std::make_unique<Value>()) {}
JsonObject::~JsonObject() = default;
JsonObject::JsonObject(const JsonObject& other) : value_(std::make_unique<Value>(*other.value_)) {}
JsonObject& JsonObject::operator=(const JsonObject& other) {
  *value_ = *other.value_;
  return *this;
}

JsonObject& JsonObject::Add(const std::string& key, double value) {
  value_->json[key] = Number(value);
  return *this;
}

JsonObject& JsonObject::Add(const std::string& key, long long value) {
  value_->json[key] = value;
  return *this;
}

JsonObject& JsonObject::Add(const std::string& key, bool value) {
  value_->json[key] = value;
  return *this;
}

JsonObject& JsonObject::Add(const std::string& key, const std::string& value) {
  value_->json[key] = value;
  return *this;
}

JsonObject& JsonObject::Add(const std::string& key, const JsonObject& value) {
  value_->json[key] = value.value_->json;
  return *this;
}

JsonObject& JsonObject::Add(const std::string& key, const std::vector<double>& values) {
  nlohmann::ordered_json array = nlohmann::ordered_json::array();
  for (const double v : values) array.push_back(Number(v));
  value_->json[key] = std::move(array);
  return *this;
}

JsonObject& JsonObject::Add(const std::string& key, const std::vector<JsonObject>& values) {
  nlohmann::ordered_json array = nlohmann::ordered_json::array();
  for (const JsonObject& v : values) array.push_back(v.value_->json);
  value_->json[key] = std::move(array);
  return *this;
}

std::string JsonObject::Text() const {
  // invalid UTF-8 (a map name from a binary file) is replaced rather than thrown on
  return value_->json.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

}  // namespace aerobox
