#include "scenario/sweep.h"

#include <glob.h>
#include <toml++/toml.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>

#include "common/error.h"
#include "common/quoting.h"
#include "map/read_file.h"
#include "scenario/toml_fields.h"

namespace aerobox {
namespace fs = std::filesystem;
using toml_read::FolderName;
using toml_read::LineOf;
namespace {

// A TOML value as text that TOML and JSON both read the same: numbers (a float keeps its
// point), booleans, strings in double quotes, arrays of these.
std::string ValueText(const toml::node& node, const SourceLocation& where,
                      const std::string& field) {
  if (const auto* i = node.as_integer()) return std::to_string(i->get());
  if (const auto* f = node.as_floating_point()) {
    const double value = f->get();
    if (!std::isfinite(value)) throw InputError(where, field, "expected a finite number");
    char text[32];
    for (int digits = 1; digits <= 17; ++digits) {  // the shortest text that reads back the same
      std::snprintf(text, sizeof(text), "%.*g", digits, value);
      if (std::strtod(text, nullptr) == value) break;
    }
    std::string shown = text;
    if (shown.find_first_of(".eE") == std::string::npos) shown += ".0";
    return shown;
  }
  if (const auto* b = node.as_boolean()) return b->get() ? "true" : "false";
  if (const auto* s = node.as_string()) return JsonQuoted(s->get());
  if (const auto* a = node.as_array()) {
    std::string text = "[";
    for (size_t i = 0; i < a->size(); ++i) {
      text += (i ? ", " : "") + ValueText(*a->get(i), where, field);
    }
    return text + "]";
  }
  throw InputError(where, field, "expected a number, a boolean, a string or an array of these");
}

// The scenario files a pattern names, relative to the sweep file's folder, sorted.
std::vector<std::string> Expand(const std::string& pattern, const fs::path& folder,
                                const SourceLocation& where) {
  const fs::path full = fs::path(pattern).is_absolute() ? fs::path(pattern) : folder / pattern;
  glob_t found{};
  const int code = glob(full.c_str(), 0, nullptr, &found);
  std::vector<std::string> files;
  for (size_t i = 0; code == 0 && i < found.gl_pathc; ++i) files.emplace_back(found.gl_pathv[i]);
  globfree(&found);
  if (files.empty()) {
    const bool wildcard = pattern.find_first_of("*?[") != std::string::npos;
    throw InputError(where, "scenarios",
                     "'" + pattern + "' " + (wildcard ? "matches no file" : "is not there") +
                         " (looked in " +
                         (fs::path(pattern).is_absolute() ? std::string("/")
                                                          : folder.lexically_normal().string()) +
                         ")");
  }
  for (const std::string& file : files) {
    if (fs::path(file).extension() != ".toml") {
      throw InputError(where, "scenarios",
                       "'" + pattern + "' names " + file + ", which is not a scenario (.toml)");
    }
  }
  return files;
}

std::uint64_t Fnv1a(const std::string& text) {
  std::uint64_t hash = 1469598103934665603ULL;
  for (const char c : text) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ULL;
  }
  return hash;
}

}  // namespace

void SweepKeep::Describe(Archive& a) {
  a.Integer({"video", "", "how many runs (the first ones) write video.mp4"}, &video, 0, kMaxRuns);
  a.Boolean({"telemetry", "", "every run keeps telemetry.csv"}, &telemetry);
  a.Boolean({"overview", "", "every run keeps overview.png"}, &overview);
  a.Boolean({"report", "", "every run keeps its report.html (the sweep writes its own page)"},
            &report);
}

std::string SweepRunId(const std::string& label, std::uint64_t seed,
                       const std::vector<Setting>& settings) {
  std::string key = label + "\n" + std::to_string(seed);
  for (const Setting& s : settings) key += "\n" + s.key + "=" + s.value;
  char id[20];
  std::snprintf(id, sizeof(id), "%016llx", static_cast<unsigned long long>(Fnv1a(key)));
  return id;
}

Shard ParseShard(const std::string& text, const std::string& option) {
  Shard shard;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%d/%d%c", &shard.index, &shard.count, &tail) != 2 ||
      shard.count < 1 || shard.index < 0 || shard.index >= shard.count) {
    throw InputError({"command line", 0}, option,
                     "expected i/N with 0 <= i < N, e.g. 0/4, got '" + text + "'");
  }
  return shard;
}

namespace {

// `scenarios`: files and globs, each file once; `labels` as the sweep names them.
void ReadScenarioList(const toml::node& node, const std::string& path, const fs::path& folder,
                      Sweep* sweep, std::vector<std::string>* labels) {
  const std::string name = "scenarios";
  const SourceLocation where{path, LineOf(node)};
  const toml::array* list = node.as_array();
  if (list == nullptr || list->empty()) {
    throw InputError(where, name, "expected a non-empty list of scenario files or globs");
  }
  std::set<std::string> seen;
  for (const toml::node& item : *list) {
    const std::optional<std::string> pattern = item.value<std::string>();
    const SourceLocation at{path, LineOf(item)};
    if (!pattern || pattern->empty()) throw InputError(at, name, "expected a file or glob");
    for (const std::string& file : Expand(*pattern, folder, at)) {
      // absolute: a run's summary names its files the same from any folder or host
      const std::string absolute = fs::absolute(file).lexically_normal().string();
      if (seen.insert(fs::weakly_canonical(file).string()).second) {
        sweep->scenarios.push_back(absolute);
        // the label: as the sweep names it, relative to its folder (or absolute)
        labels->push_back(fs::path(*pattern).is_absolute()
                              ? absolute
                              : fs::path(file)
                                    .lexically_normal()
                                    .lexically_relative(folder.lexically_normal())
                                    .string());
      }
    }
  }
}

// `seeds`: a count, or a list of distinct seeds.
void ReadSeeds(const toml::node& node, const std::string& path, Sweep* sweep) {
  const std::string name = "seeds";
  const SourceLocation where{path, LineOf(node)};
  if (const std::optional<std::int64_t> count = node.value<std::int64_t>()) {
    if (*count < 1 || *count > 100000) {
      throw InputError(where, name, "expected a count from 1 to 100000, or a list of seeds");
    }
    for (std::int64_t s = 1; s <= *count; ++s) sweep->seeds.push_back(s);
  } else if (const toml::array* list = node.as_array(); list && !list->empty()) {
    std::set<std::uint64_t> seen;
    for (const toml::node& item : *list) {
      const std::optional<std::int64_t> seed = item.value<std::int64_t>();
      if (!seed || *seed < 0) {
        throw InputError({path, LineOf(item)}, name, "expected non-negative integer seeds");
      }
      if (!seen.insert(*seed).second) {
        throw InputError({path, LineOf(item)}, name,
                         "seed " + std::to_string(*seed) + " is given twice");
      }
      sweep->seeds.push_back(static_cast<std::uint64_t>(*seed));
    }
  } else {
    throw InputError(where, name, "expected a count (5) or a non-empty list of seeds");
  }
}

// [grid]: scenario keys, each with its values as TOML text; `lines`: each key's line.
void ReadGrid(const toml::node& node, const std::string& path, Sweep* sweep,
              std::vector<int>* lines) {
  const std::string name = "grid";
  const SourceLocation where{path, LineOf(node)};
  const toml::table* grid = node.as_table();
  if (grid == nullptr) throw InputError(where, name, "expected a table [grid]");
  if (grid->empty()) {
    throw InputError(where, "grid",
                     "the grid is empty: give a scenario key and its values, "
                     "\"trajectory.max_speed\" = [2.0, 4.0], or leave [grid] out");
  }
  for (const auto& [grid_key, values] : *grid) {
    const std::string field = "grid." + std::string(grid_key.str());
    const SourceLocation at{path, LineOf(values)};
    const std::string scenario_key(grid_key.str());
    if (scenario_key == "seed") {
      throw InputError(at, field, "the sweep's seeds come from `seeds`, not the grid");
    }
    if (scenario_key == "name") {
      throw InputError(at, field, "a run's name is its id: the grid cannot set it");
    }
    const toml::array* list = values.as_array();
    if (list == nullptr || list->empty()) {
      throw InputError(at, field,
                       "expected a non-empty list of values, e.g. [2.0, 4.0] (one value: "
                       "[2.0])");
    }
    std::vector<std::string> texts;
    std::set<std::string> seen;
    for (const toml::node& value : *list) {
      texts.push_back(ValueText(value, {path, LineOf(value)}, field));
      if (!seen.insert(texts.back()).second) {
        throw InputError({path, LineOf(value)}, field, texts.back() + " is given twice");
      }
    }
    sweep->grid.emplace_back(scenario_key, texts);
    lines->push_back(LineOf(values));
  }
}

// Every cell of the grid, the first key varying slowest.
std::vector<std::vector<Setting>> GridCells(const Sweep& sweep, const std::vector<int>& lines,
                                            int grid_line) {
  const std::string& path = sweep.file;
  const std::vector<int>& grid_lines = lines;
  std::vector<std::vector<Setting>> cells = {{}};
  for (size_t k = 0; k < sweep.grid.size(); ++k) {
    std::vector<std::vector<Setting>> grown;
    for (const std::vector<Setting>& cell : cells) {
      for (const std::string& value : sweep.grid[k].second) {
        std::vector<Setting> next = cell;
        next.push_back({sweep.grid[k].first, value, {path, grid_lines[k]}, ""});
        grown.push_back(std::move(next));
      }
    }
    cells = std::move(grown);
    if (cells.size() * sweep.scenarios.size() * sweep.seeds.size() > kMaxRuns) {
      throw InputError({path, grid_line}, "grid",
                       "more than " + std::to_string(kMaxRuns) + " runs: split the sweep");
    }
  }

  return cells;
}

// Each run, its set-up loaded once: a setting the scenario refuses is reported at its grid
// line.
void ExpandRuns(const std::vector<std::vector<Setting>>& cells,
                const std::vector<std::string>& labels, Sweep* sweep) {
  const std::string& path = sweep->file;
  std::set<std::string> ids;
  for (size_t k = 0; k < sweep->scenarios.size(); ++k) {
    const std::string& scenario = sweep->scenarios[k];
    const std::string& label = labels[k];
    LoadFlightSetup(scenario, SetupOverrides());  // the scenario's own errors, at its own lines
    for (const std::vector<Setting>& cell : cells) {
      SetupOverrides overrides;
      overrides.settings = cell;
      try {
        LoadFlightSetup(scenario, overrides);
      } catch (const InputError& e) {
        if (e.where().file == path) throw;
        throw InputError({path, cell.empty() ? 1 : cell.front().where.line}, "grid",
                         "in " + label + ": " + e.what());
      }
      for (const std::uint64_t seed : sweep->seeds) {
        SweepRun run;
        run.index = static_cast<int>(sweep->runs.size());
        run.scenario = scenario;
        run.label = label;
        run.seed = seed;
        run.settings = cell;
        run.id = SweepRunId(label, seed, cell);
        run.video = run.index < sweep->keep.video;
        if (!ids.insert(run.id).second) {
          throw InputError({path, 1}, "scenarios", "two runs of " + label + " have the same id");
        }
        sweep->runs.push_back(std::move(run));
      }
    }
  }
}

}  // namespace

Sweep ReadSweep(const std::string& path) {
  const std::string text = ReadTextFile(path);
  toml::table table;
  try {
    table = toml::parse(text, path);
  } catch (const toml::parse_error& error) {
    throw InputError({path, static_cast<int>(error.source().begin.line)}, "TOML",
                     std::string(error.description()));
  }
  Sweep sweep;
  sweep.file = path;
  sweep.name = fs::path(path).stem().string();
  const fs::path folder =
      fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
  int grid_line = 0;
  std::vector<int> grid_lines;  // each grid key's line
  bool seeds_given = false;
  std::vector<std::string> labels;  // per scenario
  for (const auto& [key, node] : table) {
    const std::string name(key.str());
    const SourceLocation where{path, LineOf(node)};
    if (name == "name") {
      sweep.name = FolderName(node, path, name);
    } else if (name == "scenarios") {
      ReadScenarioList(node, path, folder, &sweep, &labels);
    } else if (name == "seeds") {
      seeds_given = true;
      ReadSeeds(node, path, &sweep);
    } else if (name == "grid") {
      grid_line = LineOf(node);
      ReadGrid(node, path, &sweep, &grid_lines);
    } else if (name == "keep") {
      const toml::table* keep = node.as_table();
      if (keep == nullptr) throw InputError(where, name, "expected a table [keep]");
      toml_read::ReadFields(*keep, path, "keep.", &sweep.keep);
    } else {
      const std::string nearest = NearestName(name, {"name", "scenarios", "seeds", "grid", "keep"});
      throw InputError(where, name,
                       "unknown key (expected name, scenarios, seeds, [grid] or [keep])" +
                           (nearest.empty() ? "" : "; did you mean " + nearest + "?"));
    }
  }
  if (sweep.scenarios.empty()) throw InputError({path, 1}, "scenarios", "missing key");
  if (!seeds_given) sweep.seeds = {1};
  ExpandRuns(GridCells(sweep, grid_lines, grid_line), labels, &sweep);
  return sweep;
}

}  // namespace aerobox
