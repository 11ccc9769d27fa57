// Python objects in aerobox's seams, and the dictionaries at the edge, in RotorPy's conventions:
// world frame ENU (z up), body frame FLU, quaternions [i, j, k, w], body rates in the body frame,
// SI units. Shared by the module (module.cpp) and the interpreter the command embeds
// (embedded.cpp); pybind11's types stay inside src/python.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <exception>
#include <string>
#include <vector>

#include "control/controller.h"
#include "map/map.h"
#include "mission/flight.h"
#include "planning/planner.h"
#include "trajectory/generators.h"
#include "vehicle/quad_params.h"

namespace aerobox::python {

namespace py = pybind11;

// RotorPy's state dict: x [m], v [m/s], q [i, j, k, w], w [rad/s, body], wind [m/s] at the
// vehicle and rotor_speeds [rad/s] (from the produced thrusts through k_eta).
py::dict StateDict(const State& state, const Vec4& rotor_thrusts, const QuadParams& vehicle,
                   const Vec3& wind_W);
// The inverse for x, v, q and w (sim.reset(state=...)); throws py::value_error naming the key.
State StateFromDict(py::handle dict);
// The rotors' thrusts [N] of a state dict: from its rotor_speeds [rad/s] (RotorPy's state) when
// it has them, else those that hover. Throws py::value_error naming the key.
Vec4 RotorThrustsFromState(py::handle dict, const QuadParams& vehicle);

// RotorPy's flat-output dict: x, x_dot, x_ddot, x_dddot, x_ddddot [m, m/s, ...], yaw [rad],
// yaw_dot [rad/s].
py::dict FlatDict(const FlatOutput& flat);
// What a trajectory's update(t) returned; x is required, the rest default to 0. Throws
// py::value_error naming `who`, the time and the key.
FlatOutput FlatFromDict(py::handle dict, double t, const std::string& who);

// Which of a command dict's keys fly (RotorPy's control abstractions); kAuto takes the first
// present of cmd_motor_thrusts, cmd_motor_speeds, cmd_thrust with cmd_moment, cmd_w or cmd_q.
enum class CommandChoice {
  kAuto,
  kMotorThrusts,
  kMotorSpeeds,
  kThrustMoment,
  kThrustRates,
  kThrustAttitude
};
// "auto", "cmd_motor_thrusts", "cmd_motor_speeds", "cmd_ctbm", "cmd_ctbr" or "cmd_ctatt";
// throws py::value_error otherwise.
CommandChoice ParseCommandChoice(const std::string& name);
// A controller's answer as a command. Extra keys are ignored. Throws py::value_error naming
// `who`, the time and the key for a missing key, a wrong shape or a non-finite value.
ControlCommand CommandFromDict(py::handle dict, CommandChoice choice, const QuadParams& vehicle,
                               double t, const std::string& who);

// What aerobox made of a vehicle dict beyond reading it, for the user to see.
struct VehicleNotes {
  // keys with no counterpart, each with why (a zero of a term not modelled is not listed)
  std::vector<std::pair<std::string, std::string>> ignored;
  std::vector<std::string> adjusted;  // a value changed to be simulated, from -> to and why
  std::vector<std::string> added;     // a key absent, the value aerobox took and why
};
// A vehicle from RotorPy's quad_params dict (or flightsim's: arm_length, k_thrust, k_drag, and
// no motor lag: its rotors follow the command after one `physics_step` [s]). Throws
// py::value_error naming the key.
QuadParams VehicleFromDict(py::handle dict, double physics_step, VehicleNotes* notes);
// A vehicle as RotorPy's quad_params dict: rotor_pos as r1..r4 by the index of
// QuadParams::rotor_positions_B (RotorPy's order for the built-ins; a dict's own order for a
// vehicle read with VehicleFromDict, which keeps it as given).
py::dict VehicleDict(const QuadParams& vehicle);

// The map as flightsim's world dict: bounds.extents [xmin, xmax, ymin, ymax, zmin, zmax],
// blocks [{extents, color}] (what a MEAM620 planner reads).
py::dict WorldDict(const Map& map);

// "RuntimeError: what it said (file.py line 51, in update)": a Python exception and its
// innermost frame, on one line.
std::string DescribeError(const py::error_already_set& error);
// The exception's whole traceback as Python prints it ("Traceback (most recent call last): ..."),
// without the final newline; empty when it cannot be formatted.
std::string FormatTraceback(const py::error_already_set& error);

// A Python controller (update(t, state, flat_output) -> dict) in the Controller seam. Update
// never throws: a Python exception, or a command that is not usable (a missing key, a wrong
// shape, a non-finite value), comes back as ControlStatus::kFailed, its message naming the
// time and where it was raised, its detail the user's traceback. The exception itself is kept
// (with a note naming the time): RethrowIfFailed raises it again, traceback and all, for a
// caller in Python.
class PythonController : public Controller {
 public:
  PythonController(py::object controller, const QuadParams& vehicle, CommandChoice choice);
  void Sense(const Surroundings& now) override { now_ = now; }
  ControlStatus Update(double t, const State& state, const FlatOutput& setpoint,
                       ControlCommand* command) override;
  // Throws what made an Update fail (the user's exception, or py::value_error); else nothing.
  void RethrowIfFailed() const;

 private:
  py::object update_;
  QuadParams vehicle_;
  CommandChoice choice_;
  Surroundings now_;
  std::exception_ptr error_;
};

// A Python trajectory (update(t) -> flat-output dict; `duration` or `t_final` [s] when it has
// one) as a Reference flown to `t_final` [s] (or its duration when t_final is not positive).
// Calls update once per time. `duration_known` tells whether the object gave its duration.
Reference PythonReference(py::object trajectory, double t_final, bool* duration_known);

// A Python planner: plan(world, start, goal) -> (N, 3) array from start to goal, checked leg
// by leg against the validity functions (kPathBlocked names the first leg that is not free).
class PythonPlanner : public Planner {
 public:
  PythonPlanner(py::object planner, py::dict world, const PlannerContext& context);
  PlanResult Plan(const Vec3& start, const Vec3& goal) override;

 private:
  py::object planner_;
  py::dict world_;
  PlannerContext context_;
};

// A Python trajectory class in the TrajectoryGenerator seam: made with the path, Class(path)
// ((N, 3) array), then sampled at `rate` [Hz] over its duration into quintic Hermite segments
// (SampledTrajectory) and checked against the world.
class PythonGenerator : public TrajectoryGenerator {
 public:
  explicit PythonGenerator(py::object cls, double rate = 200.0);
  TrajectoryResult Generate(const std::vector<Vec3>& path, const TrajectoryWorld& world) override;

 private:
  py::object class_;
  double rate_;
};

// "file.py:Class": imports the file as a module (its folder first on sys.path) and returns the
// class. Throws py::value_error for a malformed spec; the import's own exception otherwise.
py::object LoadClass(const std::string& spec);

// (N, 3) array <-> points [m]; throws py::value_error naming `what` for another shape or a
// non-finite value.
std::vector<Vec3> PointsFromArray(py::handle array, const std::string& what);
py::object PointsArray(const std::vector<Vec3>& points);
Vec3 PointFrom(py::handle value, const std::string& what);
// "who at t = T s", the time rounded to a microsecond: how messages name a call.
std::string At(const std::string& who, double t);
py::array_t<double> Vec3Array(const Vec3& v);  // (3,) [m, m/s, ...]

}  // namespace aerobox::python
