#include "app/cli.h"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "app/exit_codes.h"
#include "app/files.h"
#include "app/scenario.h"
#include "common/error.h"
#include "common/number_format.h"
#include "scene/scene_mjcf.h"
#include "sim/simulation.h"

namespace aerobox {
namespace {

// "X,Y,Z" from the command line [m].
std::optional<Vec3> ParsePointOption(const std::string& text, const char* option) {
  if (text.empty()) return std::nullopt;
  Vec3 point;
  std::istringstream fields(text);
  std::string field;
  int count = 0;
  while (std::getline(fields, field, ',')) {
    if (count < 3 && ParseNumber(field, &point[count]) && std::isfinite(point[count])) {
      ++count;
    } else {
      count = 4;
      break;
    }
  }
  if (count != 3) {
    throw InputError({"command line", 0}, option,
                     "expected three numbers X,Y,Z in metres, got '" + text + "'");
  }
  return point;
}

const char* FormatName(MapFormat format) {
  switch (format) {
    case MapFormat::kTxt:
      return "TXT";
    case MapFormat::kJson:
      return "JSON";
    case MapFormat::kCsv:
      return "CSV";
  }
  return "?";
}

std::string Describe(const Aabb& box) {
  return "[" + FormatVector(box.min, ", ") + "] .. [" + FormatVector(box.max, ", ") + "]";
}

// Start and goal must lie inside the bounds (on them is allowed: published maps do it) and
// outside every box.
void CheckEndpoint(const FlightSetup& setup, const Vec3& point, const std::string& what,
                   const std::string& origin) {
  const std::string field = what + " (" + origin + ")";
  const SourceLocation where{setup.map.source, 0};
  if (!setup.map.bounds.Contains(point)) {
    throw InputError(
        where, field,
        FormatVector(point, ", ") + " lies outside the bounds " + Describe(setup.map.bounds));
  }
  if (const auto box = FirstOverlappingBox(setup.map, Aabb{point, point})) {
    const Box& b = setup.map.boxes[*box];
    throw InputError(
        {setup.map.source, b.line}, field,
        FormatVector(point, ", ") + " lies inside " + b.name + " " + Describe(b.extent));
  }
}

int RunCheck(const FlightSetup& setup, std::ostream& out) {
  const Map& map = setup.map;
  const auto row = [&out](const char* label) -> std::ostream& {
    return out << std::left << std::setw(10) << label;
  };
  row("map") << map.source << " (" << FormatName(setup.map_format) << ")\n";
  row("name") << setup.name << "\n";
  row("bounds") << Describe(map.bounds) << " m (" << FormatVector(map.bounds.Size(), " x ")
                << " m)\n";
  row("boxes") << map.boxes.size() << "\n";
  row("start") << FormatVector(setup.start, ", ") << " (" << setup.start_origin << ")\n";
  if (setup.goal) {
    row("goal") << FormatVector(*setup.goal, ", ") << " (" << setup.goal_origin << ")\n";
  } else {
    row("goal") << "none given\n";
  }
  const std::vector<size_t> outside = BoxesOutsideBounds(map);
  row("outside") << outside.size() << (outside.size() == 1 ? " box reaches" : " boxes reach")
                 << " outside the bounds (kept)\n";
  for (const size_t i : outside) {
    out << "            " << map.boxes[i].name << " (line " << map.boxes[i].line
        << "): " << Describe(map.boxes[i].extent) << "\n";
  }

  CheckEndpoint(setup, setup.start, "start", setup.start_origin);
  if (setup.goal) CheckEndpoint(setup, *setup.goal, "goal", setup.goal_origin);

  const Simulation sim = Simulation::FromXml(SceneMjcfFor(setup), map.source + " (scene)");
  row("scene") << "loads in MuJoCo " << mj_versionString() << " (" << sim.model()->ngeom
               << " geoms, " << sim.model()->nbody << " bodies)\n";
  row("result") << "ok\n";
  return kExitReachedGoal;
}

int RunScene(const FlightSetup& setup, const std::string& output, std::ostream& out) {
  const std::string xml = SceneMjcfFor(setup);
  if (output.empty() || output == "-") {
    out << xml;
  } else {
    WriteFileAtomically(output, xml);
  }
  return kExitReachedGoal;
}

int RunModel(const std::string& output, std::ostream& out) {
  const std::string xml = VehicleModelMjcf(QuadParams());
  if (output.empty() || output == "-") {
    out << xml;
  } else {
    WriteFileAtomically(output, xml);
  }
  return kExitReachedGoal;
}

}  // namespace

int RunCli(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  CLI::App app("aerobox: a headless flight sandbox for a Tello-sized quadrotor in MuJoCo",
               "aerobox");
  app.set_version_flag("--version", std::string("aerobox ") + AEROBOX_VERSION + " (MuJoCo " +
                                        mj_versionString() + ")");
  app.require_subcommand(1);

  std::string input;
  std::string start_text;
  std::string goal_text;
  std::string output;
  const auto add_input = [&](CLI::App* command) {
    command->add_option("input", input, "scenario.toml or map file (.txt, .json, .csv)")
        ->required();
    command->add_option("--start", start_text, "start X,Y,Z [m], overriding the scenario's");
    command->add_option("--goal", goal_text, "goal X,Y,Z [m], overriding the scenario's");
  };

  CLI::App* scene = app.add_subcommand("scene", "write the MuJoCo MJCF scene of a map");
  add_input(scene);
  scene->add_option("-o,--output", output, "output file (default: standard output)");

  CLI::App* check = app.add_subcommand(
      "check", "validate a map or scenario and print a summary (exit 2 when it is bad)");
  add_input(check);

  CLI::App* model = app.add_subcommand("model", "write the vehicle's MJCF model alone");
  model->add_option("-o,--output", output, "output file (default: standard output)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error, out, err);
    return code == 0 ? kExitReachedGoal : kExitBadInput;
  }

  try {
    if (model->parsed()) return RunModel(output, out);
    SetupOverrides overrides;
    overrides.start = ParsePointOption(start_text, "--start");
    overrides.goal = ParsePointOption(goal_text, "--goal");
    const FlightSetup setup = LoadFlightSetup(input, overrides);
    if (scene->parsed()) return RunScene(setup, output, out);
    return RunCheck(setup, out);
  } catch (const InputError& error) {
    err << "aerobox: error: " << error.what() << "\n";
    return kExitBadInput;
  } catch (const std::invalid_argument& error) {
    err << "aerobox: error: " << error.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& error) {
    err << "aerobox: unexpected error: " << error.what() << "\n";
    return kExitUnexpected;
  }
}

}  // namespace aerobox
