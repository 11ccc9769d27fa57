// Reading a scenario's or a sweep's TOML tables: the scenario library's own header (toml++'s
// types appear in it; no other library includes it). Every reader names the file, the line and
// the key of a bad value.
#pragma once

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/schema.h"
#include "common/types.h"

namespace aerobox::toml_read {

int LineOf(const toml::node& node);
// [x, y, z] in metres, finite.
Vec3 ReadPoint(const toml::node& node, const std::string& file, const char* key);
// A number within [low, high].
double Number(const toml::node& node, const std::string& file, const std::string& key, double low,
              double high);
bool Boolean(const toml::node& node, const std::string& file, const std::string& key);
// A 3-vector: an array of 3 numbers, or one number for all three; each within [low, high].
Vec3 Vector(const toml::node& node, const std::string& file, const std::string& key, double low,
            double high);
std::string Text(const toml::node& node, const std::string& file, const std::string& key);
// A name that is also a folder's: a non-empty string without '/'.
std::string FolderName(const toml::node& node, const std::string& file, const std::string& key);

// A table read through a struct's Describe (common/schema.h): each field's key is looked up,
// read, and checked against the field's range.
class TomlFields : public Archive {
 public:
  // Keys in `skip` belong to another reader (a registered plug-in's own, of the same name as a
  // built-in's field): this one leaves them alone.
  TomlFields(const toml::table& table, std::string file, std::string prefix,
             std::vector<std::string> skip = {})
      : table_(table), file_(std::move(file)), prefix_(std::move(prefix)), skip_(std::move(skip)) {}
  using Archive::Integer;

  void Number(const Field& field, double* value, double low, double high) override {
    if (const toml::node* node = Find(field)) {
      *value = toml_read::Number(*node, file_, prefix_ + field.name, low, high);
    }
  }
  void Integer(const Field& field, long* value, long low, long high) override {
    const toml::node* node = Find(field);
    if (node == nullptr) return;
    const std::optional<double> number = node->is_number() ? node->value<double>() : std::nullopt;
    if (!number || !(*number >= static_cast<double>(low) && *number <= static_cast<double>(high)) ||
        std::floor(*number) != *number) {
      throw InputError(
          {file_, LineOf(*node)}, prefix_ + field.name,
          "expected a whole number from " + std::to_string(low) + " to " + std::to_string(high));
    }
    *value = static_cast<long>(*number);
  }
  void Boolean(const Field& field, bool* value) override {
    if (const toml::node* node = Find(field)) {
      *value = toml_read::Boolean(*node, file_, prefix_ + field.name);
    }
  }
  void Vector(const Field& field, Vec3* value, double low, double high) override {
    if (const toml::node* node = Find(field)) {
      *value = toml_read::Vector(*node, file_, prefix_ + field.name, low, high);
    }
  }
  void Choice(const Field& field, std::string* value,
              const std::vector<std::string>& choices) override {
    const toml::node* node = Find(field);
    if (node == nullptr) return;
    const std::optional<std::string> text = node->value<std::string>();
    if (!text || std::find(choices.begin(), choices.end(), *text) == choices.end()) {
      std::vector<std::string> quoted;
      for (const std::string& choice : choices) quoted.push_back("\"" + choice + "\"");
      throw InputError({file_, LineOf(*node)}, prefix_ + field.name,
                       "expected " + ListOfNames(quoted));
    }
    *value = *text;
  }
  void Text(const Field& field, std::string* value) override {
    if (const toml::node* node = Find(field)) {
      *value = toml_read::Text(*node, file_, prefix_ + field.name);
    }
  }
  void Points(const Field& field, Vec3* points, int count, double low, double high) override {
    const toml::node* node = Find(field);
    if (node == nullptr) return;
    const toml::array* rows = node->as_array();
    if (rows == nullptr || static_cast<int>(rows->size()) != count) {
      throw InputError({file_, LineOf(*node)}, prefix_ + field.name,
                       "expected " + std::to_string(count) + " points [[x, y, z], ...]" +
                           (*field.unit != '\0' ? std::string(" in ") + field.unit : ""));
    }
    for (int i = 0; i < count; ++i) {
      points[i] =
          toml_read::Vector((*rows)[static_cast<size_t>(i)], file_,
                            prefix_ + field.name + "[" + std::to_string(i) + "]", low, high);
    }
  }
  void Signs(const Field& field, int* signs, int count) override {
    const toml::node* node = Find(field);
    if (node == nullptr) return;
    const toml::array* items = node->as_array();
    const std::string key = prefix_ + field.name;
    if (items == nullptr || static_cast<int>(items->size()) != count) {
      throw InputError({file_, LineOf(*node)}, key,
                       "expected " + std::to_string(count) + " signs, e.g. [1, -1, 1, -1]");
    }
    for (int i = 0; i < count; ++i) {
      const std::optional<int64_t> sign = (*items)[static_cast<size_t>(i)].value<int64_t>();
      if (!sign || (*sign != 1 && *sign != -1)) {
        throw InputError({file_, LineOf(*node)}, key + "[" + std::to_string(i) + "]",
                         std::string("expected 1 or -1 (") + field.meaning + ")");
      }
      signs[i] = static_cast<int>(*sign);
    }
  }

 private:
  const toml::node* Find(const Field& field) const {
    if (std::find(skip_.begin(), skip_.end(), field.name) != skip_.end()) return nullptr;
    return table_.get(field.name);
  }

  const toml::table& table_;
  std::string file_;
  std::string prefix_;
  std::vector<std::string> skip_;
};

// The keys of a table that are not its struct's fields: read by hand before or after it, or a
// registered kind's own (which win over a built-in field of the same name).
struct OtherKeys {
  std::vector<std::string> before, after;
  std::vector<std::string> plugin;  // the kind's own keys
  std::string kind;                 // which kind: controller kind "mine"
};

// Reads `table` into `params` through its Describe. Any key that is neither a field nor one of
// `other` is refused, listing the keys (in the order: before, the fields, after; then the
// kind's own) and naming the one it looks like a misspelling of.
template <typename Params>
void ReadFields(const toml::table& table, const std::string& file, const std::string& prefix,
                Params* params, const OtherKeys& other = {}) {
  std::vector<std::string> names = other.before;
  for (const std::string& name : FieldNames(*params)) names.push_back(name);
  names.insert(names.end(), other.after.begin(), other.after.end());
  std::vector<std::string> all = names;
  all.insert(all.end(), other.plugin.begin(), other.plugin.end());
  for (const auto& [key, node] : table) {
    const std::string name(key.str());
    if (std::find(all.begin(), all.end(), name) != all.end()) continue;
    std::string own;
    for (const std::string& key_name : other.plugin) own += (own.empty() ? "" : ", ") + key_name;
    const std::string nearest = NearestName(name, all);
    throw InputError({file, LineOf(node)}, prefix + name,
                     "unknown key (expected " + ListOfNames(names) +
                         (own.empty() ? "" : "; " + other.kind + " adds " + own) + ")" +
                         (nearest.empty() ? "" : "; did you mean " + nearest + "?"));
  }
  TomlFields reader(table, file, prefix, other.plugin);
  params->Describe(reader);
}

// A registered plug-in's own keys in its table, after the built-in ones: read through its
// parameters' Describe.
void ReadPluginKeys(const toml::table& table, const std::string& file, const std::string& prefix,
                    PluginParameters* params);

}  // namespace aerobox::toml_read
