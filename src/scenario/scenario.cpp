#include "scenario/scenario.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "common/error.h"
#include "common/number_format.h"
#include "common/quoting.h"
#include "common/schema.h"
#include "control/controllers.h"
#include "map/map_reader.h"
#include "map/read_file.h"
#include "planning/planner.h"
#include "scenario/toml_fields.h"
#include "scene/scene_mjcf.h"
#include "vehicle/quad_params.h"

namespace aerobox {
namespace fs = std::filesystem;
using namespace toml_read;  // the readers of TOML values and tables (toml_fields.h)
namespace {

// [planner]'s and [trajectory]'s keys as a struct with a Describe, for ReadFields and the key
// reference.
struct PlannerKeys {
  PlanningSettings* settings;
  void Describe(Archive& a) { settings->DescribePlanner(a); }
};
struct TrajectoryKeys {
  PlanningSettings* settings;
  void Describe(Archive& a) { settings->DescribeTrajectory(a); }
};

void ReadPlanner(const toml::table& table, const std::string& file, PlanningSettings* settings) {
  // the kind first, whatever the table's order: a registered planner brings its own keys
  if (const toml::node* kind = table.get("kind")) {
    const std::optional<std::string> value = kind->value<std::string>();
    if (!value || (*value != "auto" && Planners().Find(*value) == nullptr)) {
      throw InputError({file, LineOf(*kind)}, "planner.kind",
                       "expected auto, " + Planners().NameList());
    }
    settings->planner = *value;
    settings->planner_params = Planners().Parameters(*value);
  }
  // the table's keys through PlanningSettings' Describe; the waypoints by hand; then the
  // plug-in's own
  PlannerKeys keys{settings};
  ReadFields(table, file, "planner.", &keys,
             {{"kind"},
              {"waypoints"},
              FieldNames(settings->planner_params),
              "planner kind \"" + settings->planner + "\""});
  if (table.get("lattice_spacing") != nullptr) {
    settings->lattice.vertical_spacing = settings->lattice.spacing;
  }
  if (const toml::node* node = table.get("waypoints")) {
    const toml::array* points = node->as_array();
    if (points == nullptr) {
      throw InputError({file, LineOf(*node)}, "planner.waypoints",
                       "expected an array of points [[x, y, z], ...]");
    }
    settings->waypoints.clear();
    for (size_t i = 0; i < points->size(); ++i) {
      const std::string field = "planner.waypoints[" + std::to_string(i) + "]";
      settings->waypoints.push_back(ReadPoint((*points)[i], file, field.c_str()));
    }
  }
  ReadPluginKeys(table, file, "planner.", &settings->planner_params);
}

void ReadTrajectory(const toml::table& table, const std::string& file, PlanningSettings* settings) {
  // the table's keys through PlanningSettings' Describe; these by hand
  TrajectoryKeys keys{settings};
  ReadFields(table, file, "trajectory.", &keys, {{}, {"method", "file"}, {}, ""});
  for (const auto& [key, node] : table) {
    const std::string name(key.str());
    const std::string field = "trajectory." + name;
    if (name == "method") {
      const std::optional<std::string> text = node.value<std::string>();
      if (!text || TrajectoryGenerators().Find(*text) == nullptr) {
        throw InputError({file, LineOf(node)}, field,
                         "expected " + TrajectoryGenerators().NameList());
      }
      settings->trajectory_method = *text;
    } else if (name == "file") {
      const std::optional<std::string> value = node.value<std::string>();
      if (!value || value->empty())
        throw InputError({file, LineOf(node)}, field, "expected a file name");
      const std::string path = (fs::path(file).parent_path() / *value).lexically_normal().string();
      std::string text;
      try {
        text = ReadTextFile(path);
      } catch (const InputError& e) {
        throw InputError({file, LineOf(node)}, field, e.what());
      }
      std::istringstream in(text);
      settings->given_trajectory = ReadTrajectoryCsv(in, path);
    }
  }
  const toml::node* method = table.get("method");
  if (method != nullptr && settings->trajectory_method == "given" &&
      settings->given_trajectory.empty()) {
    throw InputError({file, LineOf(*method)}, "trajectory.method",
                     "\"given\" needs the trajectory's file: trajectory.file = \"trajectory.csv\"");
  }
}

// [vehicle]: the kind first (whatever the table's order), then overrides of its values, then
// one check of the whole; a vehicle that is not physical is reported at the table.
void ReadVehicle(const toml::table& table, const std::string& file, int table_line,
                 Scenario* scenario) {
  if (const toml::node* kind = table.get("kind")) {
    const std::string name = Text(*kind, file, "vehicle.kind");
    const std::optional<QuadParams> builtin = BuiltinVehicle(name);
    if (!builtin) {
      throw InputError({file, LineOf(*kind)}, "vehicle.kind",
                       "expected \"tello\" or \"crazyflie\", got \"" + name + "\"");
    }
    scenario->vehicle_kind = name;
    scenario->vehicle = *builtin;
  }
  QuadParams& v = scenario->vehicle;
  // QuadParams' fields through its Describe; RotorPy's names for them by hand
  ReadFields(table, file, "vehicle.", &v,
             {{"kind"}, {"rotor_speed_max", "rotor_speed_min", "moment_coefficient"}, {}, ""});
  std::optional<double> speed_min, speed_max, moment_coefficient;
  int speed_line = 0;
  const bool thrust_given =
      table.get("max_rotor_thrust") != nullptr || table.get("min_rotor_thrust") != nullptr;
  for (const auto& [key, node] : table) {
    const std::string name(key.str());
    const std::string field = "vehicle." + name;
    const int line = LineOf(node);
    if (name == "rotor_speed_max" || name == "rotor_speed_min") {
      (name == "rotor_speed_max" ? speed_max : speed_min) = Number(node, file, field, 0, 1e5);
      speed_line = line;
    } else if (name == "moment_coefficient") {
      moment_coefficient = Number(node, file, field, 1e-18, 1);
    }
  }
  // RotorPy's names, in rotor speeds and k_m, through the (possibly new) thrust coefficient
  if ((speed_max || speed_min) && thrust_given) {
    throw InputError({file, speed_line}, "vehicle.rotor_speed_max",
                     "give the rotor limits as thrusts or as speeds, not both");
  }
  if (speed_max) v.max_rotor_thrust = v.ThrustAtSpeed(*speed_max);
  if (speed_min) v.min_rotor_thrust = v.ThrustAtSpeed(*speed_min);
  if (moment_coefficient) v.yaw_moment_per_thrust = *moment_coefficient / v.thrust_coefficient;
  try {
    v.Validate();
  } catch (const std::invalid_argument& e) {
    throw InputError({file, table_line}, "vehicle", e.what());
  }
}

void ReadController(const toml::table& table, const std::string& file, int table_line,
                    ControllerConfig* config) {
  // the kind first, whatever the table's order: a registered controller brings its own keys
  if (const toml::node* kind = table.get("kind")) {
    config->kind = Text(*kind, file, "controller.kind");
    if (Controllers().Find(config->kind) == nullptr) {
      throw InputError({file, LineOf(*kind)}, "controller.kind",
                       "expected " + Controllers().NameList() + ", got \"" + config->kind + "\"");
    }
    config->params = Controllers().Parameters(config->kind);
  }
  ReadFields(
      table, file, "controller.", config,
      {{"kind"}, {}, FieldNames(config->params), "controller kind \"" + config->kind + "\""});
  if (table.get("max_tilt") != nullptr) config->se3.max_tilt = config->cascade.max_tilt;
  ReadPluginKeys(table, file, "controller.", &config->params);
  // the rate must divide the 1 kHz physics rate
  const double steps = 1000.0 / config->rate;
  if (std::abs(steps - std::round(steps)) > 1e-9) {
    const toml::node* rate = table.get("rate");
    throw InputError({file, rate != nullptr ? LineOf(*rate) : table_line}, "controller.rate",
                     "must divide the 1000 Hz physics rate (e.g. 1000, 500, 250, 200, 100)");
  }
  try {
    config->Validate();
  } catch (const std::invalid_argument& e) {
    throw InputError({file, table_line}, "controller", e.what());
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

// A trajectory as aerobox's trajectory.csv writes it: a header t,x,y,z,vx,vy,vz,ax,ay,az, then
// one sample per row [s, m, m/s, m/s^2].
std::vector<TrajectorySample> ReadTrajectoryCsv(std::istream& in, const std::string& file) {
  static const char* const kHeader = "t,x,y,z,vx,vy,vz,ax,ay,az";
  std::string line;
  int number = 0;
  std::vector<TrajectorySample> samples;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (number == 1) {
      if (line != kHeader) {
        throw InputError({file, 1}, "header", std::string("expected ") + kHeader);
      }
      continue;
    }
    if (line.empty()) continue;
    std::istringstream fields(line);
    std::string field;
    double values[10];
    int count = 0;
    while (std::getline(fields, field, ',')) {
      if (count >= 10 || !ParseNumber(field, &values[count]) || !std::isfinite(values[count])) {
        throw InputError({file, number}, "sample",
                         "expected 10 finite numbers t,x,y,z,vx,vy,vz,ax,ay,az");
      }
      ++count;
    }
    if (count != 10) {
      throw InputError({file, number}, "sample",
                       "expected 10 finite numbers t,x,y,z,vx,vy,vz,ax,ay,az");
    }
    TrajectorySample s;
    s.t = values[0];
    s.p_W = Vec3(values[1], values[2], values[3]);
    s.v_W = Vec3(values[4], values[5], values[6]);
    s.a_W = Vec3(values[7], values[8], values[9]);
    if (!samples.empty() && !(s.t > samples.back().t)) {
      throw InputError({file, number}, "t", "times must increase");
    }
    samples.push_back(s);
  }
  if (samples.size() < 2) throw InputError({file, number}, "", "expected at least 2 samples");
  return samples;
}

// A table or a boolean: `imu = true` or `[sensors.imu]` with keys.
const toml::table* TableOrSwitch(const toml::node& node, const std::string& file,
                                 const std::string& field, bool* enabled) {
  if (node.is_boolean()) {
    *enabled = node.as_boolean()->get();
    return nullptr;
  }
  const toml::table* table = node.as_table();
  if (table == nullptr)
    throw InputError({file, LineOf(node)}, field, "expected true, false or a table");
  *enabled = true;
  return table;
}

// [wind] through its Describe, then [[wind.gusts]] each through Gust's; checked as a whole at
// the table.
void ReadWind(const toml::table& table, const std::string& file, int table_line, WindParams* wind) {
  ReadFields(table, file, "wind.", wind, {{}, {"gusts"}, {}, ""});
  if (const toml::node* node = table.get("gusts")) {
    const toml::array* gusts = node->as_array();
    if (gusts == nullptr) {
      throw InputError({file, LineOf(*node)}, "wind.gusts",
                       "expected [[wind.gusts]] tables (start, rise, duration, peak, direction)");
    }
    wind->gusts.clear();
    for (size_t i = 0; i < gusts->size(); ++i) {
      const std::string item = "wind.gusts[" + std::to_string(i) + "]";
      const toml::table* g = (*gusts)[i].as_table();
      if (g == nullptr) throw InputError({file, LineOf((*gusts)[i])}, item, "expected a table");
      Gust gust;
      ReadFields(*g, file, item + ".", &gust);
      wind->gusts.push_back(gust);
    }
  }
  try {
    wind->Validate();
  } catch (const std::invalid_argument& e) {
    throw InputError({file, table_line}, "wind", e.what());
  }
}

void ReadAero(const toml::table& table, const std::string& file, AeroParams* aero) {
  // drag: both at once, then each on its own
  if (const toml::node* both = table.get("drag")) {
    aero->body_drag = aero->rotor_drag = Boolean(*both, file, "aero.drag");
  }
  ReadFields(table, file, "aero.", aero, {{"drag"}, {}, {}, ""});
}

void ReadImu(const toml::table& table, const std::string& file, ImuParams* imu) {
  ReadFields(table, file, "sensors.imu.", imu);
}

// The kind first (its defaults), then every key through the struct's Describe.
void ReadPositionSensor(const toml::table& table, const std::string& file,
                        PositionSensorParams* position) {
  if (table.get("kind") != nullptr) {
    PositionSensorParams given;  // read once for its kind
    ReadFields(table, file, "sensors.position.", &given);
    *position = given.kind == PositionSensorKind::kGps ? PositionSensorParams::Gps()
                                                       : PositionSensorParams();
  }
  ReadFields(table, file, "sensors.position.", position);
  position->enabled = true;
}

void ReadEstimator(const toml::table& table, const std::string& file, EstimatorParams* e) {
  ReadFields(table, file, "sensors.estimator.", e);
}

// [sensors]: imu and position, each true, false or a table; [sensors.estimator]; checked as a
// whole at the table (both sensors or neither; rates that divide the 1 kHz physics).
void ReadSensors(const toml::table& table, const std::string& file, int table_line,
                 SensorParams* sensors) {
  for (const auto& [key, node] : table) {
    const std::string name(key.str());
    const std::string field = "sensors." + name;
    if (name == "imu") {
      if (const toml::table* t = TableOrSwitch(node, file, field, &sensors->imu.enabled)) {
        ReadImu(*t, file, &sensors->imu);
      }
    } else if (name == "position") {
      bool enabled = false;
      if (const toml::table* t = TableOrSwitch(node, file, field, &enabled)) {
        ReadPositionSensor(*t, file, &sensors->position);
      }
      sensors->position.enabled = enabled;
    } else if (name == "estimator") {
      const toml::table* t = node.as_table();
      if (t == nullptr) throw InputError({file, LineOf(node)}, field, "expected a table");
      ReadEstimator(*t, file, &sensors->estimator);
    } else {
      throw InputError({file, LineOf(node)}, field,
                       "unknown key (expected imu, position or estimator)");
    }
  }
  try {
    sensors->Validate(SceneOptions().timestep);
  } catch (const std::invalid_argument& e) {
    throw InputError({file, table_line}, "sensors", e.what());
  }
}

namespace {

toml::table ParseToml(const std::string& text, const std::string& file) {
  try {
    return toml::parse(text, file);
  } catch (const toml::parse_error& error) {
    throw InputError({file, static_cast<int>(error.source().begin.line)}, "TOML",
                     std::string(error.description()));
  }
}

// Sets `setting` in the table: its dotted key names nested tables (made when missing).
void ApplySetting(const Setting& setting, toml::table* table) {
  std::vector<std::string> parts;
  std::istringstream key(setting.key);
  for (std::string part; std::getline(key, part, '.');) parts.push_back(part);
  const bool well_formed =
      !parts.empty() && setting.key.back() != '.' &&
      std::none_of(parts.begin(), parts.end(), [](const std::string& p) { return p.empty(); });
  if (!well_formed) {
    throw InputError(setting.where, setting.key,
                     "expected a scenario key, dotted for a table's: seed, trajectory.max_speed");
  }
  toml::table value;
  try {
    value = toml::parse("value = " + setting.value);
  } catch (const toml::parse_error&) {
    value.insert("value", setting.value);  // a bare word: a string
  }
  toml::table* at = table;
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    toml::node* next = at->get(parts[i]);
    if (next == nullptr) {
      at->insert(parts[i], toml::table());
      next = at->get(parts[i]);
    }
    if (!next->is_table()) {
      throw InputError(setting.where, setting.key, parts[i] + " is not a table in the scenario");
    }
    at = next->as_table();
  }
  at->insert_or_assign(parts.back(), *value.get("value"));
}

Scenario ScenarioFromTable(const toml::table& table, const std::string& file);

// The scenario read as it is, then with the settings: an error the settings bring is reported
// where the setting that brings it was given.
Scenario ScenarioWithSettings(const std::string& text, const std::string& file,
                              const std::vector<Setting>& settings) {
  const toml::table table = ParseToml(text, file);
  Scenario plain = ScenarioFromTable(table, file);
  if (settings.empty()) return plain;
  const auto blame = [&file](const Setting& setting, const InputError& e) {
    if (!setting.option.empty()) {  // a flag's value, as the flag: "--max-speed: expected ..."
      return InputError(setting.where, setting.option,
                        (e.field() == setting.key ? "" : e.field() + ": ") + e.problem());
    }
    return InputError(
        setting.where, setting.key,
        "in " + file + ": " + (e.field().empty() ? "" : e.field() + ": ") + e.problem());
  };
  toml::table all = table;
  for (const Setting& setting : settings) ApplySetting(setting, &all);
  try {
    return ScenarioFromTable(all, file);
  } catch (const InputError& e) {
    // the setting of the key refused; else the first refused on its own; else (settings that
    // fail only together) the first
    for (auto s = settings.rbegin(); s != settings.rend(); ++s) {
      if (s->key == e.field()) throw blame(*s, e);
    }
    for (const Setting& setting : settings) {
      toml::table alone = table;
      ApplySetting(setting, &alone);
      try {
        ScenarioFromTable(alone, file);
      } catch (const InputError& alone_error) {
        throw blame(setting, alone_error);
      }
    }
    throw blame(settings.front(), e);
  }
}

}  // namespace

Setting ParseSetting(const std::string& text, const std::string& option) {
  const size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0 || equals + 1 == text.size()) {
    throw InputError({"command line", 0}, option,
                     "expected KEY=VALUE, e.g. trajectory.max_speed=2.0, got '" + text + "'");
  }
  return {text.substr(0, equals), text.substr(equals + 1), {"command line", 0}, ""};
}

Scenario ReadScenario(std::istream& in, const std::string& file) {
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return ScenarioFromTable(ParseToml(buffer.str(), file), file);
}

namespace {

// A scenario's tables, each read by one function from the table and where it starts.
using SectionReader = void (*)(const toml::table&, const SourceLocation&, Scenario*);
const std::pair<const char*, SectionReader> kSections[] = {
    {"planner", [](const toml::table& t, const SourceLocation& at,
                   Scenario* s) { ReadPlanner(t, at.file, &s->planning); }},
    {"trajectory", [](const toml::table& t, const SourceLocation& at,
                      Scenario* s) { ReadTrajectory(t, at.file, &s->planning); }},
    {"vehicle", [](const toml::table& t, const SourceLocation& at,
                   Scenario* s) { ReadVehicle(t, at.file, at.line, s); }},
    {"controller",
     [](const toml::table& t, const SourceLocation& at, Scenario* s) {
       ReadController(t, at.file, at.line, &s->controller);
       s->drag_feedforward_given = t.get("drag_feedforward") != nullptr;
       s->se3_integral_given = t.get("se3_position_integral") != nullptr;
     }},
    {"flight",
     [](const toml::table& t, const SourceLocation& at, Scenario* s) {
       ReadFields(t, at.file, "flight.", &s->flight);
       s->yaw_given = s->yaw_given || t.get("yaw") != nullptr;
     }},
    {"wind", [](const toml::table& t, const SourceLocation& at,
                Scenario* s) { ReadWind(t, at.file, at.line, &s->wind); }},
    {"aero",
     [](const toml::table& t, const SourceLocation& at, Scenario* s) {
       ReadAero(t, at.file, &s->aero);
       s->aero_given = true;
     }},
    {"sensors", [](const toml::table& t, const SourceLocation& at,
                   Scenario* s) { ReadSensors(t, at.file, at.line, &s->sensors); }},
    {"sensing",
     [](const toml::table& t, const SourceLocation& at, Scenario* s) {
       ReadFields(t, at.file, "sensing.", &s->sensing);
       try {
         s->sensing.Validate();  // what one key's range cannot say: a depth camera's field
       } catch (const std::invalid_argument& e) {
         // "sensing.fov: ...": the line of the key it names
         const std::string what = e.what();
         const std::string key = what.substr(8, what.find(':') - 8);
         const toml::node* node = t.get(key);
         throw InputError({at.file, node ? LineOf(*node) : at.line}, "", what);
       }
     }},
    {"replan", [](const toml::table& t, const SourceLocation& at,
                  Scenario* s) { ReadFields(t, at.file, "replan.", &s->replan); }},
    {"swarm", [](const toml::table& t, const SourceLocation& at,
                 Scenario* s) { ReadFields(t, at.file, "swarm.", &s->swarm); }},
    {"render",
     [](const toml::table& t, const SourceLocation& at, Scenario*) {
       for (const auto& [key, node] : t) {
         throw InputError({at.file, LineOf(node)}, "render." + std::string(key.str()),
                          "unknown key (this version defines no keys in [render])");
       }
     }},
};

const SectionReader* FindSection(const std::string& name) {
  for (const auto& [section, read] : kSections) {
    if (name == section) return &read;
  }
  return nullptr;
}

// A file named relative to the scenario's folder.
std::string RelativeFile(const toml::node& node, const std::string& file, const std::string& key) {
  const std::optional<std::string> value = node.value<std::string>();
  if (!value || value->empty()) throw InputError({file, LineOf(node)}, key, "expected a file name");
  return (fs::path(file).parent_path() / *value).lexically_normal().string();
}

}  // namespace

void VehicleEntry::Describe(Archive& a) {
  a.Text({"name", "", "its name, unique: its outputs' folder and its name in messages (required)"},
         &name);
  a.Text({"kind", "", "\"tello\" or \"crazyflie\" (empty: [vehicle], with its changes)"}, &kind);
  a.Text({"controller", "", "its controller's kind (empty: [controller]'s)"}, &controller);
  a.Number({"rate", "Hz", "its controller's rate (0: [controller]'s)"}, &rate, 0, 1000);
  a.Vector({"start", "m", "where it starts, [x, y, z] (required)"}, &start, -1e6, 1e6);
  a.Vector({"goal", "m", "where it ends, [x, y, z] (this, or goals)"}, &goal, -1e6, 1e6);
}

namespace {

void ReadGoals(const toml::node& node, const std::string& file, Scenario* s);

// [[vehicles]]: an array of tables, each read through VehicleEntry's Describe.
void ReadVehicleEntries(const toml::node& node, const std::string& file, Scenario* s) {
  const toml::array* tables = node.as_array();
  if (tables == nullptr || tables->empty()) {
    throw InputError({file, LineOf(node)}, "vehicles",
                     "expected [[vehicles]] tables, one per vehicle");
  }
  for (const toml::node& item : *tables) {
    const toml::table* table = item.as_table();
    if (table == nullptr) {
      throw InputError({file, LineOf(item)}, "vehicles", "expected a [[vehicles]] table");
    }
    VehicleEntry entry;
    entry.line = LineOf(item);
    ReadFields(*table, file, "vehicles.", &entry, {{}, {"goals", "vehicle"}, {}, ""});
    for (const char* key : {"name", "start"}) {
      if (table->get(key) == nullptr) {
        throw InputError({file, entry.line}, std::string("vehicles.") + key,
                         "missing key: every [[vehicles]] table needs name, start and goal");
      }
    }
    entry.name = FolderName(*table->get("name"), file, "vehicles.name");
    // a folder of outputs beside summary.json, and a prefix of MuJoCo's names
    const bool plain = std::isalnum(static_cast<unsigned char>(entry.name[0])) &&
                       std::all_of(entry.name.begin(), entry.name.end(), [](char c) {
                         return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
                       });
    if (!plain) {
      throw InputError({file, LineOf(*table->get("name"))}, "vehicles.name",
                       "\"" + entry.name +
                           "\": expected letters, digits, _ and -, from a letter "
                           "or digit (it names the vehicle's folder of outputs)");
    }
    const toml::node* goals = table->get("goals");
    if ((goals != nullptr) == (table->get("goal") != nullptr)) {
      throw InputError({file, goals ? LineOf(*goals) : entry.line},
                       "vehicles." + entry.name + ".goal",
                       goals ? "give goal or goals, not both" : "missing key: give goal or goals");
    }
    if (goals != nullptr) {
      Scenario mission;  // goals as the top level reads them: the last is the goal
      ReadGoals(*goals, file, &mission);
      entry.via = mission.via;
      entry.goal = *mission.goal;
    }
    s->vehicle_entries.push_back(entry);
  }
}

// A [[vehicles]] entry as a vehicle of the swarm: the scenario's vehicle and controller with
// the entry's kind, controller and rate.
SwarmMember MemberOf(const VehicleEntry& entry, const toml::table* vehicle_table,
                     const Scenario& scenario, const std::string& file) {
  const SourceLocation at{file, entry.line};
  const std::string key = "vehicles." + entry.name + ".";
  SwarmMember m;
  m.name = entry.name;
  m.start = entry.start;
  m.goal = entry.goal;
  m.via = entry.via;
  m.where = at;
  m.vehicle_kind = scenario.vehicle_kind;
  m.vehicle = scenario.vehicle;
  if (!entry.kind.empty()) {
    const std::optional<QuadParams> builtin = BuiltinVehicle(entry.kind);
    if (!builtin) {
      throw InputError(at, key + "kind",
                       "expected \"tello\" or \"crazyflie\", got \"" + entry.kind + "\"");
    }
    m.vehicle_kind = entry.kind;
    m.vehicle = *builtin;
  }
  if (vehicle_table != nullptr) {  // [vehicles.vehicle]: its kind and values, as [vehicle]'s
    Scenario own;
    own.vehicle_kind = m.vehicle_kind;
    own.vehicle = m.vehicle;
    ReadVehicle(*vehicle_table, file, LineOf(*vehicle_table), &own);
    m.vehicle_kind = own.vehicle_kind;
    m.vehicle = own.vehicle;
  }
  m.controller = scenario.controller;
  if (!entry.controller.empty()) {
    if (Controllers().Find(entry.controller) == nullptr) {
      throw InputError(
          at, key + "controller",
          "expected " + Controllers().NameList() + ", got \"" + entry.controller + "\"");
    }
    m.controller.kind = entry.controller;
    m.controller.params = Controllers().Parameters(entry.controller);
  }
  if (entry.rate > 0) {
    const double steps = 1000.0 / entry.rate;
    if (std::abs(steps - std::round(steps)) > 1e-9) {
      throw InputError(at, key + "rate",
                       "must divide the 1000 Hz physics rate (e.g. 1000, 500, 250, 200, 100)");
    }
    m.controller.rate = entry.rate;
  }
  return m;
}

// The entries as vehicles, each name once; the first's start and goal stand for the scenario's
// when it gives none (the scene's camera, `aerobox check`).
void ResolveVehicles(const toml::table& table, const std::string& file, Scenario* scenario) {
  const toml::array* tables = table.get_as<toml::array>("vehicles");
  for (size_t i = 0; i < scenario->vehicle_entries.size(); ++i) {
    const VehicleEntry& entry = scenario->vehicle_entries[i];
    for (size_t j = 0; j < i; ++j) {
      if (scenario->vehicle_entries[j].name == entry.name) {
        throw InputError({file, entry.line}, "vehicles.name",
                         "\"" + entry.name + "\" is already the name of the vehicle on line " +
                             std::to_string(scenario->vehicle_entries[j].line));
      }
    }
    const toml::table* own = (*tables)[i].as_table();
    const toml::node* vehicle = own != nullptr ? own->get("vehicle") : nullptr;
    if (vehicle != nullptr && vehicle->as_table() == nullptr) {
      throw InputError({file, LineOf(*vehicle)}, "vehicles." + entry.name + ".vehicle",
                       "expected a table [vehicles.vehicle] of the vehicle's values");
    }
    scenario->vehicles.push_back(
        MemberOf(entry, vehicle ? vehicle->as_table() : nullptr, *scenario, file));
  }
  if (scenario->vehicles.empty()) return;
  for (const char* key : {"start", "goal", "goals"}) {  // each vehicle has its own
    if (const toml::node* given = table.get(key)) {
      throw InputError({file, LineOf(*given)}, key,
                       "with [[vehicles]], each vehicle's table gives its start and goal");
    }
  }
  const VehicleEntry& first = scenario->vehicle_entries.front();
  if (!scenario->start) {
    scenario->start = first.start;
    scenario->start_line = first.line;
  }
  if (!scenario->goal) {
    scenario->goal = first.goal;
    scenario->goal_line = first.line;
  }
}

void ReadGoals(const toml::node& node, const std::string& file, Scenario* s) {
  const toml::array* points = node.as_array();
  if (points == nullptr || points->empty()) {
    throw InputError({file, LineOf(node)}, "goals",
                     "expected an array of points [[x, y, z], ...] in metres");
  }
  for (size_t i = 0; i < points->size(); ++i) {
    const Vec3 p = ReadPoint((*points)[i], file, ("goals[" + std::to_string(i) + "]").c_str());
    if (i + 1 < points->size()) {
      s->via.push_back(p);
    } else {
      s->goal = p;
    }
  }
  s->goal_line = LineOf(node);
}

void ReadUnknown(const toml::node& node, const std::string& file, Scenario* s) {
  const toml::array* indices = node.as_array();
  if (indices == nullptr) {
    throw InputError({file, LineOf(node)}, "unknown",
                     "expected an array of box indices (from 0, in map order)");
  }
  for (size_t i = 0; i < indices->size(); ++i) {
    const toml::value<int64_t>* index = (*indices)[i].as_integer();
    if (index == nullptr || index->get() < 0 || index->get() > 1000000) {
      throw InputError({file, LineOf((*indices)[i])}, "unknown[" + std::to_string(i) + "]",
                       "expected a box index (an integer from 0)");
    }
    s->unknown.push_back(static_cast<int>(index->get()));
  }
  s->unknown_line = LineOf(node);
}

void ReadSeed(const toml::node& node, const std::string& file, Scenario* s) {
  // an integer node only: toml++ would convert a float such as 2e30 by an out-of-range cast
  // (undefined behaviour; the fuzzer found it)
  const toml::value<int64_t>* value = node.as_integer();
  if (value == nullptr || value->get() < 0) {
    throw InputError({file, LineOf(node)}, "seed", "expected a non-negative integer");
  }
  s->seed = static_cast<std::uint64_t>(value->get());
}

// The keys of the top-level table, once: each one's reader and its row in the key reference.
struct TopLevelKey {
  const char* name;
  const char* unit;
  const char* value;  // the default
  const char* range;
  const char* meaning;
  void (*read)(const toml::node& node, const std::string& file, Scenario* s);
};
const TopLevelKey kTopLevel[] = {
    {"name", "", "the file's stem", "a folder name",
     "the outputs' folder name (scenario.toml: its folder's name)",
     [](const toml::node& n, const std::string& f, Scenario* s) {
       s->name = FolderName(n, f, "name");
     }},
    {"map", "", "", "a file name",
     "the map (required): .txt, .json or .csv, relative to the scenario",
     [](const toml::node& n, const std::string& f, Scenario* s) {
       s->map_path = RelativeFile(n, f, "map");
       s->map_line = LineOf(n);
     }},
    {"start", "m", "the map's", "[x, y, z]", "where the flight starts",
     [](const toml::node& n, const std::string& f, Scenario* s) {
       s->start = ReadPoint(n, f, "start");
       s->start_line = LineOf(n);
     }},
    {"goal", "m", "the map's", "[x, y, z]", "where the flight ends (or goals)",
     [](const toml::node& n, const std::string& f, Scenario* s) {
       s->goal = ReadPoint(n, f, "goal");
       s->goal_line = LineOf(n);
     }},
    {"goals", "m", "", "points [[x, y, z], ...]", "a mission through each in order (or goal)",
     [](const toml::node& n, const std::string& f, Scenario* s) { ReadGoals(n, f, s); }},
    {"stop_at_goals", "", "false", "true or false",
     "stop at each of the goals (for hold) instead of flying through",
     [](const toml::node& n, const std::string& f, Scenario* s) {
       s->stop_at_goals = Boolean(n, f, "stop_at_goals");
     }},
    {"hold", "s", "0", "0 to 600", "how long a stop at a goal lasts",
     [](const toml::node& n, const std::string& f, Scenario* s) {
       s->hold = Number(n, f, "hold", 0, 600);
     }},
    {"unknown", "", "[]", "box indices [0, 3, ...]",
     "boxes the planner does not know (from 0, in map order); [sensing] reveals them",
     [](const toml::node& n, const std::string& f, Scenario* s) { ReadUnknown(n, f, s); }},
    {"unknown_fraction", "", "0", "0 to 1", "a seeded share of the map's boxes, unknown",
     [](const toml::node& n, const std::string& f, Scenario* s) {
       s->unknown_fraction = Number(n, f, "unknown_fraction", 0, 1);
       s->unknown_line = LineOf(n);
     }},
    {"unknown_map", "", "", "a file name",
     "another map whose boxes are added to the scene, unknown to the planner",
     [](const toml::node& n, const std::string& f, Scenario* s) {
       s->unknown_map = RelativeFile(n, f, "unknown_map");
       s->unknown_line = LineOf(n);
     }},
    {"seed", "", "1", "an integer from 0", "the random seed of planning, wind and sensors",
     [](const toml::node& n, const std::string& f, Scenario* s) { ReadSeed(n, f, s); }},
    {"vehicles", "", "[]", "[[vehicles]] tables",
     "several vehicles in one world, one table each (below); [swarm] keeps them apart",
     [](const toml::node& n, const std::string& f, Scenario* s) { ReadVehicleEntries(n, f, s); }},
};

// "unknown key (expected name, map, ..., [planner], ...)" and the key it looks like.
std::string UnknownTopLevelKey(const std::string& name) {
  std::vector<std::string> keys, shown;
  for (const TopLevelKey& key : kTopLevel) keys.push_back(key.name);
  for (const std::string& key : keys) shown.push_back(key == "vehicles" ? "[[vehicles]]" : key);
  for (const auto& section : kSections) {
    keys.push_back(section.first);
    shown.push_back("[" + std::string(section.first) + "]");
  }
  const std::string nearest = NearestName(name, keys);
  return "unknown key (expected " + ListOfNames(shown) + ")" +
         (nearest.empty() ? "" : "; did you mean " + nearest + "?");
}

// One top-level key or table into `scenario`.
void ReadTopLevel(const std::string& name, const toml::node& node, const std::string& file,
                  Scenario* scenario) {
  for (const TopLevelKey& key : kTopLevel) {
    if (name == key.name) return key.read(node, file, scenario);
  }
  const SectionReader* read = FindSection(name);
  if (read == nullptr) throw InputError({file, LineOf(node)}, name, UnknownTopLevelKey(name));
  const toml::table* section = node.as_table();
  if (section == nullptr) {
    throw InputError({file, LineOf(node)}, name, "expected a table [" + name + "]");
  }
  (*read)(*section, {file, LineOf(node)}, scenario);
}

Scenario ScenarioFromTable(const toml::table& table, const std::string& file) {
  Scenario scenario;
  scenario.file = file;
  // the file's stem, so that several scenarios in one folder write to their own outputs; a
  // file called scenario.toml is named after its folder (scenes/<name>/scenario.toml)
  const fs::path absolute = fs::absolute(fs::path(file));
  scenario.name = absolute.stem() == "scenario" ? absolute.parent_path().filename().string()
                                                : absolute.stem().string();
  if (table.get("goal") != nullptr && table.get("goals") != nullptr) {
    throw InputError({file, LineOf(*table.get("goal"))}, "goal", "give goal or goals, not both");
  }
  for (const auto& [key, node] : table) ReadTopLevel(std::string(key.str()), node, file, &scenario);
  ResolveVehicles(table, file, &scenario);
  // a missing key belongs to the top-level table, which starts at line 1
  if (scenario.map_path.empty()) throw InputError({file, 1}, "map", "missing key 'map'");
  // a speed cap within the vehicle's own top speed (the schema's range is the fastest
  // vehicle's)
  const double cap = scenario.planning.trajectory.max_speed, top = scenario.vehicle.max_speed;
  if (const toml::node* given = table.at_path("trajectory.max_speed").node(); given && cap > top) {
    throw InputError({file, LineOf(*given)}, "trajectory.max_speed",
                     "expected 0.01 to " + FormatNumber(top) + " m/s (the " +
                         scenario.vehicle_kind + "'s top speed), got " + FormatNumber(cap));
  }
  return scenario;
}

}  // namespace

namespace {

FlightSetup SetupFrom(const std::string& path, std::optional<Scenario> scenario,
                      const SetupOverrides& overrides);

}  // namespace

FlightSetup LoadFlightSetup(const std::string& path, const SetupOverrides& overrides) {
  std::optional<Scenario> scenario;
  if (fs::path(path).extension() == ".toml") {
    scenario = ScenarioWithSettings(ReadTextFile(path), path, overrides.settings);
  } else if (!overrides.settings.empty()) {
    // a bare map is the scenario that names it and nothing else: the settings change that
    const std::string alone = "map = " + JsonQuoted(fs::path(path).filename().string()) + "\n";
    scenario = ScenarioWithSettings(alone, path, overrides.settings);
  }
  return SetupFrom(path, std::move(scenario), overrides);
}

FlightSetup LoadFlightSetupFromText(const std::string& text, const std::string& file,
                                    const SetupOverrides& overrides) {
  return SetupFrom(file, ScenarioWithSettings(text, file, overrides.settings), overrides);
}

namespace {

// The map the set-up flies: the scenario's, or the file itself.
void ReadSetupMap(const std::string& path, const std::optional<Scenario>& scenario,
                  FlightSetup* setup) {
  const std::string map_path = scenario ? scenario->map_path : path;
  std::string map_text;
  try {
    map_text = ReadTextFile(map_path);
  } catch (const InputError& e) {
    if (!scenario) throw;
    // the scenario's line that names the map, rather than the file that is not there
    throw InputError({path, scenario->map_line}, "map", e.what());
  }
  std::istringstream map_stream(map_text);
  setup->map_format = DetectMapFormat(map_path, map_text.substr(0, 64));
  setup->map = ReadMap(map_stream, map_path, setup->map_format);
  // a scenario names its map: scenes keep their map in a file called map.json
  if (scenario) setup->map.name = scenario->name;
  setup->name = setup->map.name;
}

// The scenario's tables, and the defaults that follow from them.
void ApplyScenarioTables(const std::optional<Scenario>& scenario, FlightSetup* setup) {
  if (scenario) {
    setup->planning = scenario->planning;
    setup->vehicle_kind = scenario->vehicle_kind;
    setup->vehicle = scenario->vehicle;
    setup->controller = scenario->controller;
    setup->flight = scenario->flight;
    setup->wind = scenario->wind;
    setup->aero = scenario->aero;
    setup->sensors = scenario->sensors;
    setup->stop_at_goals = scenario->stop_at_goals;
    setup->hold = scenario->hold;
    setup->sensing = scenario->sensing;
    setup->replan = scenario->replan;
    setup->vehicles = scenario->vehicles;
    setup->swarm = scenario->swarm;
  }
  // wind moves the vehicle through drag only: it comes with drag unless [aero] says otherwise
  if (setup->wind.Enabled() && !(scenario && scenario->aero_given)) {
    setup->aero.body_drag = setup->aero.rotor_drag = true;
  }
  FollowTheAir(scenario && scenario->drag_feedforward_given,
               scenario && scenario->se3_integral_given, setup);
}

// The start and goal beside the map: "<map stem>.startgoal.txt", or RBE595's own layout,
// maps/mapN.txt with startandgoal/mapN.txt (beside maps/, or inside the map's folder).
std::optional<StartGoal> SideFile(const std::string& map_path, fs::path* side_path) {
  const fs::path map_folder = fs::path(map_path).parent_path();
  const std::string stem = fs::path(map_path).stem().string();
  *side_path = map_folder / (stem + ".startgoal.txt");
  std::error_code ec;
  for (const fs::path& candidate : {map_folder / (stem + ".startgoal.txt"),
                                    map_folder / ".." / "startandgoal" / (stem + ".txt"),
                                    map_folder / "startandgoal" / (stem + ".txt")}) {
    if (fs::is_regular_file(candidate, ec)) {
      *side_path = candidate.lexically_normal();
      break;
    }
  }
  if (!fs::is_regular_file(*side_path, ec)) return std::nullopt;
  std::istringstream text(ReadTextFile(side_path->string()));
  return ReadStartGoal(text, side_path->string());
}

// The start (when one is given) and the goals, each from the first place that gives it: the
// command line, the scenario, the map file, the start/goal file beside it.
std::optional<Vec3> StartAndGoals(const std::string& path, const std::optional<Scenario>& scenario,
                                  const SetupOverrides& overrides, FlightSetup* setup) {
  const std::string& map_path = scenario ? scenario->map_path : path;
  fs::path side_path;
  const std::optional<StartGoal> side_file = SideFile(map_path, &side_path);
  const auto from_side_file = [&](bool start) -> std::optional<Vec3> {
    if (!side_file) return std::nullopt;
    return start ? side_file->start : side_file->goal;
  };
  const SourceLocation command_line{"command line", 0};
  const SourceLocation in_map{map_path, setup->map.start_goal_line};
  const SourceLocation in_side_file{side_path.string(), 0};
  const std::optional<Vec3> start =
      FirstGiven({{overrides.start, "command line", command_line},
                  {scenario ? scenario->start : std::nullopt,
                   "scenario",
                   {path, scenario ? scenario->start_line : 0}},
                  {setup->map.start, "map file", in_map},
                  {from_side_file(true), "start/goal file", in_side_file}},
                 &setup->start_origin, &setup->start_where);
  setup->goal = FirstGiven({{overrides.goal, "command line", command_line},
                            {scenario ? scenario->goal : std::nullopt,
                             "scenario",
                             {path, scenario ? scenario->goal_line : 0}},
                            {setup->map.goal, "map file", in_map},
                            {from_side_file(false), "start/goal file", in_side_file}},
                           &setup->goal_origin, &setup->goal_where);
  // the mission's goals before the last: the command line's replace the scenario's
  if (overrides.goal) {
    setup->via = overrides.via;
  } else if (scenario && setup->goal_origin == "scenario") {
    setup->via = scenario->via;
  }
  return start;
}

// Boxes unknown to the planner: another map's boxes join the scene, unknown; then the listed
// indices and the seeded share of the map's own.
void AddUnknownBoxes(const std::string& path, const Scenario& scenario, FlightSetup* setup) {
  const SourceLocation at{path, scenario.unknown_line};
  const size_t own = setup->map.boxes.size();
  if (!scenario.unknown_map.empty()) {
    std::string text;
    try {
      text = ReadTextFile(scenario.unknown_map);
    } catch (const InputError& e) {
      throw InputError(at, "unknown_map", e.what());
    }
    std::istringstream in(text);
    const Map extra = ReadMap(in, scenario.unknown_map,
                              DetectMapFormat(scenario.unknown_map, text.substr(0, 64)));
    for (Box box : extra.boxes) {
      box.name = "unknown_" + box.name;
      setup->map.boxes.push_back(box);
    }
  }
  if (scenario.unknown.empty() && !(scenario.unknown_fraction > 0) &&
      setup->map.boxes.size() <= own) {
    return;
  }
  Map own_boxes = setup->map;
  own_boxes.boxes.resize(own);
  try {
    setup->unknown =
        UnknownBoxes(own_boxes, scenario.unknown, scenario.unknown_fraction, setup->seed);
  } catch (const std::invalid_argument& e) {
    throw InputError(at, "unknown", e.what());
  }
  setup->unknown.resize(setup->map.boxes.size(), true);
}

// Where the vehicle starts when nothing says: on the floor clear of walls, else (a scene needs
// no start) at the top of the map, where planning refuses it.
void DefaultStartOf(const std::string& map_path, FlightSetup* setup) {
  // 0.3 m keeps the default start clear of walls by more than the vehicle's own size
  const std::optional<Vec3> fallback =
      DefaultStart(setup->map, 0.3, 0.5 * setup->vehicle.collision_size.z());
  setup->start_where = {map_path, 0};
  if (fallback) {
    setup->start = *fallback;
    setup->start_origin = "default";
  } else {
    const Aabb& bounds = setup->map.bounds;
    setup->start = Vec3(bounds.Center().x(), bounds.Center().y(), bounds.max.z());
    setup->start_origin = kNoStart;
  }
}

// Every vehicle of several starts and ends inside the map, and no two start inside each other.
void CheckVehicles(const FlightSetup& setup) {
  const auto& vehicles = setup.vehicles;
  for (size_t i = 0; i < vehicles.size(); ++i) {
    const SwarmMember& m = vehicles[i];
    std::vector<std::pair<Vec3, std::string>> points = {{m.start, "start"}, {m.goal, "goal"}};
    for (size_t k = 0; k < m.via.size(); ++k) {
      points.push_back({m.via[k], "goals[" + std::to_string(k) + "]"});
    }
    for (const auto& [point, key] : points) {
      if (!setup.map.bounds.Contains(point)) {
        throw InputError(m.where, "vehicles." + m.name + "." + key,
                         "(" + FormatVector(point, ", ") + ") m is outside the map's bounds (" +
                             FormatVector(setup.map.bounds.min, ", ") + ") .. (" +
                             FormatVector(setup.map.bounds.max, ", ") + ") m");
      }
    }
    const Vec3 rest = VehicleRestPosition(setup.map, m.vehicle, m.start);
    for (size_t j = 0; j < i; ++j) {
      const SwarmMember& other = vehicles[j];
      const double apart =
          (rest - VehicleRestPosition(setup.map, other.vehicle, other.start)).norm();
      const double least = VehicleRadius(m.vehicle) + VehicleRadius(other.vehicle);
      if (apart < least) {
        throw InputError(m.where, "vehicles." + m.name + ".start",
                         "starts " + FormatNumber(std::round(apart * 1000) / 1000) + " m from " +
                             other.name + ", inside it (their radii add up to " +
                             FormatNumber(std::round(least * 1000) / 1000) + " m)");
      }
    }
  }
}

FlightSetup SetupFrom(const std::string& path, std::optional<Scenario> scenario,
                      const SetupOverrides& overrides) {
  if (scenario && !scenario->vehicles.empty() && (overrides.start || overrides.goal)) {
    throw InputError({"command line", 0}, overrides.start ? "--start" : "--goal",
                     "the scenario's [[vehicles]] give each vehicle its own start and goal " +
                         std::string("(line ") +
                         std::to_string(scenario->vehicles.front().where.line) + " of " +
                         scenario->file + ")");
  }
  FlightSetup setup;
  ReadSetupMap(path, scenario, &setup);
  setup.seed = overrides.seed.value_or(scenario ? scenario->seed : 1);
  ApplyScenarioTables(scenario, &setup);
  std::optional<Vec3> start = StartAndGoals(path, scenario, overrides, &setup);
  if (scenario) AddUnknownBoxes(path, *scenario, &setup);
  // a depth camera looks along body x: unless the yaw was chosen, it turns with the travel, or
  // the vehicle would fly sideways into what it cannot see
  if (scenario && !scenario->yaw_given && setup.HasUnknown() &&
      setup.sensing.kind != SensingParams::Kind::kOmni) {
    setup.flight.face_travel = true;
  }
  if (setup.planning.trajectory_method == "given" && !setup.planning.given_trajectory.empty()) {
    // a given trajectory starts and ends where it does
    const SourceLocation in_trajectory{path, 0};
    start = setup.planning.given_trajectory.front().p_W;
    setup.start_origin = "trajectory file";
    setup.start_where = in_trajectory;
    setup.goal = setup.planning.given_trajectory.back().p_W;
    setup.goal_origin = "trajectory file";
    setup.goal_where = in_trajectory;
  }
  if (start) {
    setup.start = *start;
  } else {
    DefaultStartOf(scenario ? scenario->map_path : path, &setup);
  }
  CheckVehicles(setup);
  return setup;
}

}  // namespace

namespace {

// One table of the key reference.
struct KeyTable {
  std::string name;
  std::string what;
  std::vector<KeyRow> rows;
};

// [planner]'s and [trajectory]'s rows: PlanningSettings', and those read by hand.
std::vector<KeyTable> PlanningKeyTables() {
  PlanningSettings planning;  // the defaults a scenario starts from
  PlannerKeys planner_keys{&planning};
  std::vector<KeyRow> planner = KeyRowsOf(planner_keys, "planner");
  planner.insert(planner.begin(), {"planner.kind", "", "\"" + planning.planner + "\"",
                                   "auto, " + Planners().NameList(),
                                   "auto: the lattice for a map wider than 200 m, RRT* otherwise"});
  planner.push_back({"planner.waypoints", "m", "[]", "points [[x, y, z], ...]",
                     "kind \"waypoints\": the path goes start, these, goal"});
  TrajectoryKeys trajectory_keys{&planning};
  std::vector<KeyRow> trajectory = KeyRowsOf(trajectory_keys, "trajectory");
  trajectory.insert(
      trajectory.end(),
      {{"trajectory.method", "", "\"" + planning.trajectory_method + "\"",
        TrajectoryGenerators().NameList(), "the generator: min-snap (ours), a baseline, or given"},
       {"trajectory.file", "", "", "a file name",
        "method \"given\": a trajectory.csv to fly, relative to the scenario"}});
  return {
      {"planner", "the path: RRT*, the lattice, given waypoints, or a registered planner", planner},
      {"trajectory", "the trajectory along the path", trajectory}};
}

// [vehicle]'s rows: QuadParams', the kind, and RotorPy's names for its values.
std::vector<KeyRow> VehicleKeyRows() {
  std::vector<KeyRow> vehicle = KeyRows<QuadParams>("vehicle");
  vehicle.insert(vehicle.begin(), {"vehicle.kind", "", "\"tello\"", "\"tello\" or \"crazyflie\"",
                                   "the built-in vehicle whose values the other keys change"});
  vehicle.insert(vehicle.end(),
                 {{"vehicle.rotor_speed_max", "rad/s", "", "0 to 1e+05",
                   "RotorPy's limit as a speed, through thrust_coefficient (not with the thrusts)"},
                  {"vehicle.rotor_speed_min", "rad/s", "", "0 to 1e+05", "... the least"},
                  {"vehicle.moment_coefficient", "N m/(rad/s)^2", "", "1e-18 to 1",
                   "RotorPy's k_m: sets yaw_moment_per_thrust = k_m / thrust_coefficient"}});
  return vehicle;
}

// The top-level table's keys (kTopLevel).
KeyTable TopLevelKeyTable() {
  KeyTable table{"", "the keys outside any table: the map, the flight's ends, the seed", {}};
  for (const TopLevelKey& key : kTopLevel) {
    table.rows.push_back({key.name, key.unit, key.value, key.range, key.meaning});
  }
  return table;
}

// Every built-in table's rows, in the page's order.
std::vector<KeyTable> BuiltInKeyTables() {
  const ControllerConfig control;  // the defaults a scenario starts from
  std::vector<KeyRow> controller = KeyRows<ControllerConfig>("controller");
  controller.insert(controller.begin(),
                    {"controller.kind", "", "\"" + control.kind + "\"", Controllers().NameList(),
                     "the controller: the built-ins (cascade, geometric se3, incremental indi) or "
                     "a registered one"});
  std::vector<KeyRow> aero = KeyRows<AeroParams>("aero");
  aero.insert(aero.begin(), {"aero.drag", "", "false", "true or false",
                             "body_drag and rotor_drag at once (read first)"});
  std::vector<KeyTable> tables = PlanningKeyTables();
  const std::vector<KeyTable> others = {
      {"vehicle", "the vehicle: a built-in kind, and any of its values changed", VehicleKeyRows()},
      {"controller", "the controller and the loops below it; a registered one's own keys below",
       controller},
      {"flight", "when a flight has reached its goal, or is lost; the yaw",
       KeyRows<FlightParams>("flight")},
      {"wind", "the wind: a mean, Dryden turbulence, and gusts ([[wind.gusts]])",
       KeyRows<WindParams>("wind")},
      {"[wind.gusts]", "one gust, a table each, in [[wind.gusts]] tables",
       KeyRows<Gust>("wind.gusts")},
      {"aero", "drag in the air (the wind is [wind])", aero},
      {"sensors.imu", "the IMU (sensors.imu = true: these defaults)",
       KeyRows<ImuParams>("sensors.imu")},
      {"sensors.position", "the position sensor (sensors.position = true: motion capture)",
       KeyRows<PositionSensorParams>("sensors.position")},
      {"sensors.estimator", "the error-state Kalman filter the controller flies on",
       KeyRows<EstimatorParams>("sensors.estimator")},
      {"sensing", "the sensor that reveals unknown boxes in flight",
       KeyRows<SensingParams>("sensing")},
      {"replan", "replanning around boxes revealed in flight", KeyRows<ReplanParams>("replan")},
      {"[vehicles]",
       "one vehicle of several in one world, a table each in [[vehicles]] tables; the rest of "
       "the scenario is shared",
       KeyRows<VehicleEntry>("vehicles")},
      {"swarm", "how several vehicles keep apart, and their downwash",
       KeyRows<SwarmParams>("swarm")},
  };
  tables.insert(tables.end(), others.begin(), others.end());
  return tables;
}

// Registered plug-ins' own keys, each under the kind that brings them.
std::vector<KeyTable> PluginKeyTables() {
  std::vector<KeyTable> plugins;
  const auto add_plugins = [&plugins](const std::string& table, const auto& registry) {
    for (const std::string& name : registry.Names()) {
      PluginParameters params = registry.Parameters(name);
      if (params.empty()) continue;
      plugins.push_back({table + "] kind = \"" + name,
                         "the " + table + " " + name + "'s own keys, beside the table's others",
                         KeyRowsOf(params, table)});
    }
  };
  add_plugins("controller", Controllers());
  add_plugins("planner", Planners());
  return plugins;
}

}  // namespace

std::string ScenarioKeyReference() {
  std::ostringstream out;
  out << "# Scenario keys\n\n"
      << "Generated by `aerobox keys` from the parameter structs' own descriptions (a test fails "
         "when this page is not what the code says). Every key is set in a scenario's table, "
         "with `--set TABLE.KEY=VALUE` on the command line, or in a sweep's grid; a value "
         "outside its range is refused naming the file, line and key, and a misspelt key is "
         "refused naming the key it looks like.\n\n"
      << "[render] defines no keys yet.\n";
  std::vector<KeyTable> all = {TopLevelKeyTable()};
  const std::vector<KeyTable> tables = BuiltInKeyTables();
  all.insert(all.end(), tables.begin(), tables.end());
  const std::vector<KeyTable> plugins = PluginKeyTables();
  all.insert(all.end(), plugins.begin(), plugins.end());
  for (const KeyTable& table : all) {
    if (table.name.empty()) {
      out << "\n## The top level\n\n";
    } else {
      out << "\n## [" << table.name << (table.name.find('=') == std::string::npos ? "]" : "\"")
          << "\n\n";
    }
    out << table.what << ".\n\n"
        << "| key | unit | default | range | meaning |\n|---|---|---|---|---|\n";
    for (const KeyRow& row : table.rows) {
      out << "| `" << row.key.substr(row.key.rfind('.') + 1) << "` | " << row.unit << " | "
          << row.value << " | " << row.range << " | " << row.meaning << " |\n";
    }
  }
  return out.str();
}

}  // namespace aerobox
