// The controller seam's contract holds for a Python controller: Update never throws; the user's
// exception, or a command that cannot be flown, comes back as the controller's failure status
// with the time, where it was raised and the traceback, and the exception itself is kept.
#include <doctest/doctest.h>
#include <pybind11/embed.h>

#include <string>

#include "python/seams.h"

namespace aerobox {
namespace {

namespace py = pybind11;

// An instance of class `name` defined by `source`, in a fresh namespace.
py::object Instance(const char* source, const char* name) {
  if (!Py_IsInitialized()) py::initialize_interpreter(/*init_signal_handlers=*/false);
  py::dict scope;
  scope["__builtins__"] = py::module_::import("builtins");
  py::exec(source, scope);
  return scope[name]();
}

constexpr const char* kControllers = R"(
import math

class Broken:
    def update(self, t, state, flat_output):
        if t > 0.2:
            return self.helper(t)
        return {"cmd_motor_thrusts": [0.2, 0.2, 0.2, 0.2]}

    def helper(self, t):
        raise RuntimeError("the user's controller broke")

class ReturnsNaN:
    def update(self, t, state, flat_output):
        return {"cmd_motor_thrusts": [math.nan, 0.2, 0.2, 0.2]}
)";

TEST_CASE("a Python controller's exception is its failure status, with the traceback") {
  python::PythonController controller(Instance(kControllers, "Broken"), QuadParams(),
                                      python::CommandChoice::kAuto);
  ControlCommand command;
  ControlStatus status;
  CHECK_NOTHROW(status = controller.Update(0.1, State(), FlatOutput(), &command));
  CHECK(status.ok());
  CHECK(command.level == CommandLevel::kRotorThrusts);
  CHECK_NOTHROW(controller.RethrowIfFailed());  // nothing failed yet

  CHECK_NOTHROW(status = controller.Update(0.3, State(), FlatOutput(), &command));
  CHECK_FALSE(status.ok());
  CHECK(status.code == ControlStatus::Code::kFailed);
  CHECK(status.message.find("controller.update at t = 0.3 s") != std::string::npos);
  CHECK(status.message.find("RuntimeError: the user's controller broke") != std::string::npos);
  CHECK(status.message.find("in helper") != std::string::npos);  // where it was raised
  // the whole traceback: the frame of update and the frame of helper that raised
  CHECK(status.detail.find("Traceback (most recent call last)") != std::string::npos);
  CHECK(status.detail.find("in update") != std::string::npos);
  CHECK(status.detail.find("in helper") != std::string::npos);
  // the user's own exception, for a caller in Python
  bool raised = false;
  try {
    controller.RethrowIfFailed();
  } catch (py::error_already_set& e) {
    raised = e.matches(PyExc_RuntimeError);
  }
  CHECK(raised);
}

TEST_CASE("a Python controller's command that cannot be flown is its failure status") {
  python::PythonController controller(Instance(kControllers, "ReturnsNaN"), QuadParams(),
                                      python::CommandChoice::kAuto);
  ControlCommand command;
  ControlStatus status;
  CHECK_NOTHROW(status = controller.Update(0.0, State(), FlatOutput(), &command));
  CHECK(status.code == ControlStatus::Code::kFailed);
  CHECK(status.message.find("'cmd_motor_thrusts' is not finite") != std::string::npos);
  CHECK(status.message.find("t = 0 s") != std::string::npos);
  CHECK_THROWS_AS(controller.RethrowIfFailed(), py::value_error);
}

}  // namespace
}  // namespace aerobox
