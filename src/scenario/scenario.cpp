#include "scenario/scenario.h"

#include <toml++/toml.h>

#include <filesystem>
#include <sstream>

#include "common/error.h"
#include "common/number_format.h"
#include "map/map_reader.h"
#include "scenario/read_file.h"
#include "vehicle/quad_params.h"

namespace aerobox {
namespace fs = std::filesystem;
namespace {

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

// A number of the [planner] table within [low, high]; InputError at its line otherwise.
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

void ReadPlanner(const toml::table& table, const std::string& file, PlanningSettings* settings) {
  RrtStarParams& rrt = settings->rrt;
  for (const auto& [key, node] : table) {
    const std::string name(key.str());
    const std::string field = "planner." + name;
    if (name == "clearance") {
      settings->collision.clearance = Number(node, file, field, 0.0, 10.0);
    } else if (name == "max_iterations") {
      rrt.max_iterations = static_cast<long>(Number(node, file, field, 0, 1e8));
    } else if (name == "time_budget") {
      rrt.time_budget = Number(node, file, field, 1e-3, 3600);
    } else if (name == "max_step") {
      rrt.max_step = Number(node, file, field, 0, 1e4);
    } else if (name == "goal_bias") {
      rrt.goal_bias = Number(node, file, field, 0, 0.99);
    } else if (name == "rewire_factor") {
      rrt.rewire_factor = Number(node, file, field, 0.01, 100);
    } else if (name == "shortcut_attempts") {
      rrt.shortcut_attempts = static_cast<int>(Number(node, file, field, 0, 1e6));
    } else if (name == "kind") {
      const std::optional<std::string> value = node.value<std::string>();
      if (!value || (*value != "auto" && *value != "rrt_star" && *value != "lattice")) {
        throw InputError({file, LineOf(node)}, field,
                         "expected \"auto\", \"rrt_star\" or \"lattice\"");
      }
      settings->planner = *value;
    } else if (name == "lattice_spacing") {
      settings->lattice.spacing = Number(node, file, field, 0.5, 100.0);
      settings->lattice.vertical_spacing = settings->lattice.spacing;
    } else if (name == "informed") {
      if (!node.is_boolean())
        throw InputError({file, LineOf(node)}, field, "expected true or false");
      rrt.informed = node.as_boolean()->get();
    } else {
      throw InputError({file, LineOf(node)}, field,
                       "unknown key (expected kind, clearance, max_iterations, time_budget, "
                       "max_step, goal_bias, rewire_factor, informed, shortcut_attempts or "
                       "lattice_spacing)");
    }
  }
}

void ReadTrajectory(const toml::table& table, const std::string& file, PlanningSettings* settings) {
  TrajectoryParams& params = settings->trajectory;
  for (const auto& [key, node] : table) {
    const std::string name(key.str());
    const std::string field = "trajectory." + name;
    if (name == "max_speed") {
      params.max_speed = Number(node, file, field, 0.01, 8.0);  // a Tello's top speed
    } else if (name == "max_accel") {
      params.max_accel = Number(node, file, field, 0.01, 10.0);
    } else if (name == "clearance") {
      settings->trajectory_clearance = Number(node, file, field, 0.0, 10.0);
    } else if (name == "corridors") {
      params.use_corridors = Boolean(node, file, field);
    } else if (name == "corridor_growth") {
      params.corridor_growth = Number(node, file, field, 0.0, 100.0);
    } else if (name == "samples_per_segment") {
      params.samples_per_segment = static_cast<int>(Number(node, file, field, 1, 1000));
    } else if (name == "max_refinements") {
      params.max_refinements = static_cast<int>(Number(node, file, field, 0, 100));
    } else if (name == "method") {
      const std::optional<std::string> text = node.value<std::string>();
      const std::optional<TrajectoryMethod> method =
          text ? ParseTrajectoryMethod(*text) : std::nullopt;
      if (!method) {
        throw InputError({file, LineOf(node)}, field,
                         "expected \"minsnap\", \"quintic\", \"cubic\" or \"septic-full\"");
      }
      settings->trajectory_method = *method;
    } else {
      throw InputError({file, LineOf(node)}, field,
                       "unknown key (expected max_speed, max_accel, clearance, corridors, "
                       "corridor_growth, samples_per_segment, max_refinements or method)");
    }
  }
}

// The first candidate that is given; its origin goes to `origin`.
struct Candidate {
  std::optional<Vec3> point;
  const char* origin;
  SourceLocation where;
};

std::optional<Vec3> FirstGiven(std::initializer_list<Candidate> candidates, std::string* origin,
                               SourceLocation* where) {
  for (const Candidate& candidate : candidates) {
    if (candidate.point) {
      *origin = candidate.origin;
      *where = candidate.where;
      return candidate.point;
    }
  }
  return std::nullopt;
}

}  // namespace

Scenario ReadScenario(std::istream& in, const std::string& file) {
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  toml::table table;
  try {
    table = toml::parse(text, file);
  } catch (const toml::parse_error& error) {
    throw InputError({file, static_cast<int>(error.source().begin.line)}, "TOML",
                     std::string(error.description()));
  }

  Scenario scenario;
  scenario.file = file;
  scenario.name = fs::absolute(fs::path(file)).parent_path().filename().string();
  for (const auto& [key, node] : table) {
    const std::string name(key.str());
    const SourceLocation where{file, LineOf(node)};
    if (name == "name") {
      const std::optional<std::string> value = node.value<std::string>();
      if (!value || value->empty() || value->find_first_of("/\\") != std::string::npos) {
        throw InputError(where, name, "expected a non-empty string without '/' (a folder name)");
      }
      scenario.name = *value;
    } else if (name == "map") {
      const std::optional<std::string> value = node.value<std::string>();
      if (!value || value->empty()) throw InputError(where, name, "expected a file name");
      scenario.map_path = (fs::path(file).parent_path() / *value).lexically_normal().string();
      scenario.map_line = LineOf(node);
    } else if (name == "start") {
      scenario.start = ReadPoint(node, file, "start");
      scenario.start_line = LineOf(node);
    } else if (name == "goal") {
      scenario.goal = ReadPoint(node, file, "goal");
      scenario.goal_line = LineOf(node);
    } else if (name == "seed") {
      // an integer node only: toml++ would convert a float such as 2e30 by an out-of-range
      // cast (undefined behaviour; the fuzzer found it)
      const toml::value<int64_t>* value = node.as_integer();
      if (value == nullptr || value->get() < 0) {
        throw InputError(where, name, "expected a non-negative integer");
      }
      scenario.seed = static_cast<std::uint64_t>(value->get());
    } else if (name == "planner") {
      const toml::table* section = node.as_table();
      if (section == nullptr) throw InputError(where, name, "expected a table [planner]");
      ReadPlanner(*section, file, &scenario.planning);
    } else if (name == "trajectory") {
      const toml::table* section = node.as_table();
      if (section == nullptr) throw InputError(where, name, "expected a table [trajectory]");
      ReadTrajectory(*section, file, &scenario.planning);
    } else if (name == "controller" || name == "render") {
      const toml::table* section = node.as_table();
      if (section == nullptr) throw InputError(where, name, "expected a table [" + name + "]");
      for (const auto& [inner, inner_node] : *section) {
        throw InputError({file, LineOf(inner_node)}, name + "." + std::string(inner.str()),
                         "unknown key (this version defines no keys in [" + name + "])");
      }
    } else {
      throw InputError(where, name,
                       "unknown key (expected name, map, start, goal, seed, [planner], "
                       "[trajectory], [controller] or [render])");
    }
  }
  // a missing key belongs to the top-level table, which starts at line 1
  if (scenario.map_path.empty()) throw InputError({file, 1}, "map", "missing key 'map'");
  return scenario;
}

FlightSetup LoadFlightSetup(const std::string& path, const SetupOverrides& overrides) {
  FlightSetup setup;
  std::string map_path = path;
  std::optional<Scenario> scenario;
  if (fs::path(path).extension() == ".toml") {
    std::istringstream text(ReadTextFile(path));
    scenario = ReadScenario(text, path);
    map_path = scenario->map_path;
  }

  std::string map_text;
  try {
    map_text = ReadTextFile(map_path);
  } catch (const InputError& e) {
    if (!scenario) throw;
    // the scenario's line that names the map, rather than the file that is not there
    throw InputError({path, scenario->map_line}, "map", e.what());
  }
  std::istringstream map_stream(map_text);
  setup.map_format = DetectMapFormat(map_path, map_text.substr(0, 64));
  setup.map = ReadMap(map_stream, map_path, setup.map_format);
  // a scenario names its map: scenes keep their map in a file called map.json
  if (scenario) setup.map.name = scenario->name;
  setup.name = setup.map.name;
  setup.seed = overrides.seed.value_or(scenario ? scenario->seed : 1);
  if (scenario) setup.planning = scenario->planning;

  std::optional<StartGoal> side_file;
  const fs::path side_path =
      fs::path(map_path).parent_path() / (fs::path(map_path).stem().string() + ".startgoal.txt");
  std::error_code ec;
  if (fs::is_regular_file(side_path, ec)) {
    std::istringstream text(ReadTextFile(side_path.string()));
    side_file = ReadStartGoal(text, side_path.string());
  }

  const auto from_side_file = [&](bool start) -> std::optional<Vec3> {
    if (!side_file) return std::nullopt;
    return start ? side_file->start : side_file->goal;
  };
  const SourceLocation command_line{"command line", 0};
  const SourceLocation in_map{map_path, setup.map.start_goal_line};
  const SourceLocation in_side_file{side_path.string(), 0};
  const std::optional<Vec3> start =
      FirstGiven({{overrides.start, "command line", command_line},
                  {scenario ? scenario->start : std::nullopt,
                   "scenario",
                   {path, scenario ? scenario->start_line : 0}},
                  {setup.map.start, "map file", in_map},
                  {from_side_file(true), "start/goal file", in_side_file}},
                 &setup.start_origin, &setup.start_where);
  setup.goal = FirstGiven({{overrides.goal, "command line", command_line},
                           {scenario ? scenario->goal : std::nullopt,
                            "scenario",
                            {path, scenario ? scenario->goal_line : 0}},
                           {setup.map.goal, "map file", in_map},
                           {from_side_file(false), "start/goal file", in_side_file}},
                          &setup.goal_origin, &setup.goal_where);
  if (start) {
    setup.start = *start;
  } else {
    const QuadParams vehicle;
    // 0.3 m keeps the default start clear of walls by more than the vehicle's own size
    const std::optional<Vec3> fallback =
        DefaultStart(setup.map, 0.3, 0.5 * vehicle.collision_size.z());
    if (!fallback) {
      throw InputError({path, 0}, "start", "no start given and no free spot on the floor found");
    }
    setup.start = *fallback;
    setup.start_origin = "default";
    setup.start_where = {map_path, 0};
  }
  return setup;
}

}  // namespace aerobox
