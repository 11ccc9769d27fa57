#include "python/embedded.h"

#include <pybind11/embed.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include "common/error.h"
#include "python/seams.h"

namespace aerobox {
namespace {

namespace py = pybind11;
namespace fs = std::filesystem;
using python::CommandChoice;

// The packages of the virtual environment the user activated (its activate script sets
// VIRTUAL_ENV), as its own python sees them, when it is of this interpreter's version: a
// --controller module may import what the user installed there with pip.
void AddActiveVirtualEnvironment() {
  const char* venv = std::getenv("VIRTUAL_ENV");
  if (venv == nullptr || *venv == '\0') return;
  const py::object version = py::module_::import("sys").attr("version_info");
  const std::string python = "python" + std::to_string(version.attr("major").cast<int>()) + "." +
                             std::to_string(version.attr("minor").cast<int>());
  const fs::path packages = fs::path(venv) / "lib" / python / "site-packages";
  if (fs::is_directory(packages)) py::module_::import("site").attr("addsitedir")(packages.string());
}

void StartInterpreter() {
  if (Py_IsInitialized()) return;
  // never finalised: the registries keep Python objects until the process ends
  // without Python's signal handlers: Ctrl-C stays aerobox's (outputs/interrupt.h)
  py::initialize_interpreter(/*init_signal_handlers=*/false);
  // a user's module may `import aerobox`: the package beside this binary, in the build tree
  // (build/python) or where it is installed (lib/python3/dist-packages), comes first
  const fs::path bin = fs::read_symlink("/proc/self/exe").parent_path();
  py::list path = py::module_::import("sys").attr("path");
  for (const fs::path& dir : {bin / "python", bin / ".." / "lib" / "python3" / "dist-packages"}) {
    if (fs::exists(dir / "aerobox" / "__init__.py"))
      path.insert(0, dir.lexically_normal().string());
  }
  AddActiveVirtualEnvironment();
}

SourceLocation Where(const std::string& spec) { return {spec.substr(0, spec.rfind(':')), 0}; }

// Runs `f`; any exception out of Python (or of the checks at its edge) becomes InputError.
template <typename F>
auto AtOption(const std::string& option, const std::string& spec, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const InputError&) {
    throw;
  } catch (const py::error_already_set& e) {
    throw InputError(Where(spec), option, python::DescribeError(e));
  } catch (const std::exception& e) {
    throw InputError(Where(spec), option, e.what());
  }
}

class EmbeddedPlanner : public Planner {
 public:
  EmbeddedPlanner(std::string spec, std::unique_ptr<Planner> inner)
      : spec_(std::move(spec)), inner_(std::move(inner)) {}
  PlanResult Plan(const Vec3& start, const Vec3& goal) override {
    return AtOption("--planner-module", spec_, [&] { return inner_->Plan(start, goal); });
  }

 private:
  std::string spec_;
  std::unique_ptr<Planner> inner_;
};

class EmbeddedGenerator : public TrajectoryGenerator {
 public:
  EmbeddedGenerator(std::string spec, std::unique_ptr<TrajectoryGenerator> inner)
      : spec_(std::move(spec)), inner_(std::move(inner)) {}
  TrajectoryResult Generate(const std::vector<Vec3>& path, const TrajectoryWorld& world) override {
    return AtOption("--trajectory-module", spec_, [&] { return inner_->Generate(path, world); });
  }

 private:
  std::string spec_;
  std::unique_ptr<TrajectoryGenerator> inner_;
};

template <typename R, typename Factory>
void RegisterOnce(R& registry, const std::string& name, Factory factory) {
  if (registry.Find(name) == nullptr) registry.Register(name, std::move(factory));
}

}  // namespace

void UsePythonModules(const PythonModules& modules, FlightSetup* setup) {
  if (!modules.any()) return;
  StartInterpreter();
  const CommandChoice choice = AtOption(
      "--command", modules.controller, [&] { return python::ParseCommandChoice(modules.command); });
  if (!modules.controller.empty()) {
    const std::string spec = modules.controller;
    const py::object cls = AtOption("--controller", spec, [&] { return python::LoadClass(spec); });
    RegisterOnce(Controllers(), spec,
                 [spec, cls, choice](const ControllerConfig&, const QuadParams& vehicle) {
                   return AtOption("--controller", spec, [&]() -> std::unique_ptr<Controller> {
                     const py::object made = cls(python::VehicleDict(vehicle));
                     return std::make_unique<python::PythonController>(made, vehicle, choice);
                   });
                 });
    setup->controller.kind = spec;
  }
  if (!modules.trajectory.empty()) {
    const std::string spec = modules.trajectory;
    const py::object cls =
        AtOption("--trajectory-module", spec, [&] { return python::LoadClass(spec); });
    RegisterOnce(TrajectoryGenerators(), spec, [spec, cls](const GeneratorConfig&) {
      return std::unique_ptr<TrajectoryGenerator>(std::make_unique<EmbeddedGenerator>(
          spec, std::make_unique<python::PythonGenerator>(cls)));
    });
    setup->planning.trajectory_method = spec;
  }
  if (!modules.planner.empty()) {
    const std::string spec = modules.planner;
    const py::object cls =
        AtOption("--planner-module", spec, [&] { return python::LoadClass(spec); });
    const Map map = setup->map;
    RegisterOnce(
        Planners(), spec, [spec, cls, map](const PlannerConfig&, const PlannerContext& context) {
          return AtOption("--planner-module", spec, [&]() -> std::unique_ptr<Planner> {
            return std::make_unique<EmbeddedPlanner>(
                spec,
                std::make_unique<python::PythonPlanner>(cls(), python::WorldDict(map), context));
          });
        });
    setup->planning.planner = spec;
  }
}

}  // namespace aerobox
