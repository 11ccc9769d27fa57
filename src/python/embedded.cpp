#include "python/embedded.h"

#include <pybind11/embed.h>

#include <cmath>
#include <memory>
#include <sstream>

#include "common/error.h"
#include "python/seams.h"

namespace aerobox {
namespace {

namespace py = pybind11;
using python::CommandChoice;

void StartInterpreter() {
  // never finalised: the registries keep Python objects until the process ends
  // without Python's signal handlers: Ctrl-C stays aerobox's (outputs/interrupt.h)
  if (!Py_IsInitialized()) py::initialize_interpreter(/*init_signal_handlers=*/false);
}

SourceLocation Where(const std::string& spec) { return {spec.substr(0, spec.rfind(':')), 0}; }

// "RuntimeError: what it said (file.py line 51, in update)": the exception and the innermost
// frame, on one line.
std::string Describe(const py::error_already_set& e) {
  std::string text = py::str(e.type().attr("__name__")).cast<std::string>() + ": " +
                     py::str(e.value()).cast<std::string>();
  py::object frame = py::reinterpret_borrow<py::object>(e.trace());
  if (frame.is_none() || !frame) return text;
  while (!frame.attr("tb_next").is_none()) frame = frame.attr("tb_next");
  const py::object code = frame.attr("tb_frame").attr("f_code");
  const std::string file = py::str(code.attr("co_filename"));
  return text + " (" + file.substr(file.rfind('/') + 1) + " line " +
         std::to_string(frame.attr("tb_lineno").cast<int>()) + ", in " +
         py::str(code.attr("co_name")).cast<std::string>() + ")";
}

// Runs `f`; any exception out of Python (or of the checks at its edge) becomes InputError, its
// message prefixed by `during` when that is given.
template <typename F>
auto AtOption(const std::string& option, const std::string& spec, F&& f,
              const std::string& during = "") -> decltype(f()) {
  try {
    return f();
  } catch (const InputError&) {
    throw;
  } catch (const py::error_already_set& e) {
    throw InputError(Where(spec), option, (during.empty() ? "" : during + ": ") + Describe(e));
  } catch (const std::exception& e) {
    throw InputError(Where(spec), option, e.what());
  }
}

std::string AtTime(const char* call, double t) {
  std::ostringstream text;
  text << call << " at t = " << std::round(t * 1e6) / 1e6 << " s";
  return text.str();
}

class EmbeddedController : public Controller {
 public:
  EmbeddedController(std::string spec, std::unique_ptr<Controller> inner)
      : spec_(std::move(spec)), inner_(std::move(inner)) {}
  bool Update(double t, const State& state, const FlatOutput& setpoint,
              ControlCommand* command) override {
    return AtOption(
        "--controller", spec_, [&] { return inner_->Update(t, state, setpoint, command); },
        AtTime("controller.update", t));
  }

 private:
  std::string spec_;
  std::unique_ptr<Controller> inner_;
};

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
                     return std::make_unique<EmbeddedController>(
                         spec, std::make_unique<python::PythonController>(made, vehicle, choice));
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
