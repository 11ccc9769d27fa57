#include "scenario/toml_fields.h"

#include "common/number_format.h"

namespace aerobox::toml_read {

int LineOf(const toml::node& node) { return static_cast<int>(node.source().begin.line); }

Vec3 ReadPoint(const toml::node& node, const std::string& file, const char* key) {
  const toml::array* array = node.as_array();
  const SourceLocation where{file, LineOf(node)};
  if (array == nullptr || array->size() != 3) {
    throw InputError(where, key, "expected an array of 3 numbers [x, y, z] in metres");
  }
  Vec3 point;
  for (int i = 0; i < 3; ++i) {
    const std::optional<double> value = (*array)[static_cast<size_t>(i)].value<double>();
    if (!value || !std::isfinite(*value)) {
      throw InputError(where, std::string(key) + "[" + std::to_string(i) + "]",
                       "expected a finite number");
    }
    point[i] = *value;
  }
  return point;
}

double Number(const toml::node& node, const std::string& file, const std::string& key, double low,
              double high) {
  const std::optional<double> value = node.is_number() ? node.value<double>() : std::nullopt;
  if (!value || !(*value >= low && *value <= high)) {
    throw InputError({file, LineOf(node)}, key,
                     "expected a number from " + FormatNumber(low) + " to " + FormatNumber(high));
  }
  return *value;
}

bool Boolean(const toml::node& node, const std::string& file, const std::string& key) {
  if (!node.is_boolean()) throw InputError({file, LineOf(node)}, key, "expected true or false");
  return node.as_boolean()->get();
}

Vec3 Vector(const toml::node& node, const std::string& file, const std::string& key, double low,
            double high) {
  if (node.is_number()) return Vec3::Constant(Number(node, file, key, low, high));
  const toml::array* array = node.as_array();
  if (array == nullptr || array->size() != 3) {
    throw InputError({file, LineOf(node)}, key, "expected a number or an array of 3 numbers");
  }
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    v[i] = Number((*array)[static_cast<size_t>(i)], file, key + "[" + std::to_string(i) + "]", low,
                  high);
  }
  return v;
}

void ReadPluginKeys(const toml::table& table, const std::string& file, const std::string& prefix,
                    PluginParameters* params) {
  TomlFields reader(table, file, prefix);
  params->Describe(reader);
}

std::string Text(const toml::node& node, const std::string& file, const std::string& key) {
  const std::optional<std::string> value = node.value<std::string>();
  if (!value) throw InputError({file, LineOf(node)}, key, "expected a string");
  return *value;
}

std::string FolderName(const toml::node& node, const std::string& file, const std::string& key) {
  const std::optional<std::string> value = node.value<std::string>();
  if (!value || value->empty() || value->find_first_of("/\\") != std::string::npos) {
    throw InputError({file, LineOf(node)}, key,
                     "expected a non-empty string without '/' (a folder name)");
  }
  return *value;
}

}  // namespace aerobox::toml_read
