// A registry by name for a seam's implementations (controllers, planners, trajectory
// generators): the built-ins are entered when the registry is first used, and a user adds more
// with Register() before a run names them.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/schema.h"

namespace aerobox {

template <typename Factory>
class Registry {
 public:
  // `parameters`: the entry's own, with their defaults (common/schema.h), which a scenario's
  // table sets by key. Throws std::invalid_argument for an empty name or one already taken.
  void Register(const std::string& name, Factory factory, PluginParameters parameters = {}) {
    if (name.empty()) throw std::invalid_argument("registry: an empty name");
    if (!entries_.emplace(name, std::move(factory)).second) {
      throw std::invalid_argument("registry: '" + name + "' is already registered");
    }
    parameters_.emplace(name, std::move(parameters));
  }
  // The default parameters of `name` (empty: it has none of its own, or it is not there).
  PluginParameters Parameters(const std::string& name) const {
    const auto it = parameters_.find(name);
    return it == parameters_.end() ? PluginParameters() : it->second;
  }
  // The factory of `name`, or nullptr.
  const Factory* Find(const std::string& name) const {
    const auto it = entries_.find(name);
    return it == entries_.end() ? nullptr : &it->second;
  }
  // Every registered name, sorted.
  std::vector<std::string> Names() const {
    std::vector<std::string> names;
    for (const auto& entry : entries_) names.push_back(entry.first);
    return names;
  }
  // "a, b or c": the names for a message.
  std::string NameList() const {
    const std::vector<std::string> names = Names();
    std::string text;
    for (size_t i = 0; i < names.size(); ++i) {
      if (i > 0) text += i + 1 == names.size() ? " or " : ", ";
      text += names[i];
    }
    return text;
  }

 private:
  std::map<std::string, Factory> entries_;
  std::map<std::string, PluginParameters> parameters_;
};

}  // namespace aerobox
