// The compiled half of the Python package `aerobox` (src/python/aerobox/__init__.py is the
// other): the set-up, planning, trajectories, the simulator and the outputs, with numpy at the
// edge. The Python half gives the documented API; names here that start with "_" are its own.
#include <mujoco/mujoco.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <tuple>

#include "common/error.h"
#include "geometry/collision_world.h"
#include "mission/flight_parts.h"
#include "mission/mission.h"
#include "mission/plan.h"
#include "outputs/files.h"
#include "outputs/flight_outputs.h"
#include "outputs/report.h"
#include "outputs/summary.h"
#include "planning/path_simplify.h"
#include "python/envs_binding.h"
#include "python/seams.h"
#include "scenario/scenario.h"
#include "scene/scene_mjcf.h"

namespace aerobox::python {
namespace {

using SetupPtr = std::shared_ptr<FlightSetup>;

// InputError and std::invalid_argument become ValueError with aerobox's message.
template <typename F>
auto Checked(F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const InputError& e) {
    throw py::value_error(e.what());
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
}

py::object OptionalPoint(const std::optional<Vec3>& p) {
  if (!p) return py::none();
  return Vec3Array(*p);
}

std::optional<Vec3> OptionalPointFrom(const py::object& value, const std::string& what) {
  if (value.is_none()) return std::nullopt;
  return PointFrom(value, what);
}

SetupOverrides Overrides(const py::object& start, const py::object& goal, const py::object& seed) {
  SetupOverrides overrides;
  overrides.start = OptionalPointFrom(start, "start");
  overrides.goal = OptionalPointFrom(goal, "goal");
  if (!seed.is_none()) {
    const long long value = seed.cast<long long>();
    if (value < 0) throw py::value_error("seed must be >= 0");
    overrides.seed = static_cast<std::uint64_t>(value);
  }
  return overrides;
}

// An aerobox trajectory: the generator's result, flown exactly (no sampling).
struct Trajectory {
  TrajectoryResult result;
  std::string method;

  py::dict Update(double t) const {
    FlatOutput flat;
    const double s = std::clamp(t, 0.0, result.trajectory.duration());
    flat.p_W = result.trajectory.Evaluate3(s, kPosition);
    if (t >= 0 && t <= result.trajectory.duration()) {
      flat.v_W = result.trajectory.Evaluate3(t, kVelocity);
      flat.a_W = result.trajectory.Evaluate3(t, kAcceleration);
      flat.j_W = result.trajectory.Evaluate3(t, kJerk);
      flat.s_W = result.trajectory.Evaluate3(t, kSnap);
    }
    return FlatDict(flat);
  }
};

// What write_outputs needs of a run: the set-up, what was planned and every control step.
struct FlightRecord {
  SetupPtr setup;
  PlanOutcome plan;
  std::vector<TelemetrySample> samples;
  FlightResult flight;
  double wall_time = 0.0;                       // [s]
  std::vector<std::string> controller_columns;  // the controller's own (its report's names)
};

// Stands in for the run's controller when its outputs are written afterwards: its columns.
class RecordedController : public Controller {
 public:
  explicit RecordedController(std::vector<std::string> columns) : columns_(std::move(columns)) {}
  ControlStatus Update(double, const State&, const FlatOutput&, ControlCommand*) override {
    return ControlStatus::Failed("a recorded run has no controller to call");
  }
  std::vector<std::string> ReportColumns() const override { return columns_; }

 private:
  std::vector<std::string> columns_;
};

// run()'s `terminate` (as RotorPy's and flightsim's): None, the flight is complete when the
// vehicle rests at the trajectory's end (an object without a duration: at its update(inf),
// from 1 s on when it starts there, else at once); False, never; a function f(t, state), when
// it returns something true (FlightStatus::kTerminated). What f raises is kept in `error`.
struct Termination {
  std::exception_ptr error;

  void Into(const py::object& terminate, const py::object& trajectory, bool duration_known,
            const Reference& reference, FlightLoop* loop) {
    if (terminate.is_none()) {
      if (!duration_known) loop->completion = OpenEnd(trajectory, reference);
    } else if (py::isinstance<py::bool_>(terminate)) {
      if (!terminate.cast<bool>()) loop->completion.kind = Completion::Kind::kNever;
    } else if (PyCallable_Check(terminate.ptr())) {
      loop->completion.kind = Completion::Kind::kNever;
      loop->terminate = [this, terminate, loop](double t, const State& state) {
        try {
          py::dict seen = StateDict(state, Vec4::Zero(), *loop->vehicle, Vec3::Zero());
          seen.attr("pop")("wind");  // the true state alone: x, v, q, w
          seen.attr("pop")("rotor_speeds");
          return py::bool_(terminate(t, seen)).cast<bool>();
        } catch (py::error_already_set&) {
          error = std::current_exception();
          return true;
        }
      };
    } else {
      throw py::value_error("terminate: expected None, False or a function f(t, state)");
    }
  }

  // flightsim's end of a trajectory without a duration: its update(inf); none when that fails
  static Completion OpenEnd(const py::object& trajectory, const Reference& reference) {
    Completion completion;
    completion.kind = Completion::Kind::kNever;
    try {
      const FlatOutput end =
          FlatFromDict(trajectory.attr("update")(INFINITY), INFINITY, "trajectory.update");
      completion.kind = Completion::Kind::kAtPoint;
      completion.point = end.p_W;
      completion.from = end.p_W == reference.evaluate(0.0, kPosition) ? 1.0 : 0.0;
    } catch (const py::error_already_set&) {
    } catch (const py::value_error&) {
    }
    return completion;
  }
};

// A copy of `setup` flying a quad_params dict, with what was ignored ((key, why) pairs),
// adjusted and added (Simulator's vehicle notes).
py::tuple WithVehicle(const FlightSetup& setup, const py::object& vehicle) {
  auto copy = std::make_shared<FlightSetup>(setup);
  VehicleNotes notes;
  copy->vehicle = VehicleFromDict(vehicle, SceneOptions{}.timestep, &notes);
  copy->vehicle_kind = "dict";
  const py::dict dict = vehicle.cast<py::dict>();
  const auto has = [&dict](const char* key) { return dict.contains(key); };
  const char* const kDrag[] = {"c_Dx", "c_Dy", "c_Dz", "k_d", "k_z"};
  if (!setup.aero.Enabled() && std::any_of(std::begin(kDrag), std::end(kDrag), has)) {
    notes.adjusted.push_back(
        "c_Dx ... k_z: read, but drag acts only with aero={'drag': True} (RotorPy's Multirotor "
        "has it on by default)");
  }
  py::list ignored;
  for (const auto& [key, why] : notes.ignored) ignored.append(py::make_tuple(key, why));
  return py::make_tuple(copy, ignored, notes.adjusted, notes.added);
}

// telemetry.csv's columns (TelemetrySchema), one array each: pandas.DataFrame(...) in one
// call. A clearance with no obstacle in range is NaN here (-1 in the CSV).
py::dict TelemetryColumns(const FlightRecord& record) {
  const TelemetrySchema schema(record.controller_columns, TelemetryExtrasFor(*record.setup));
  const std::vector<std::string>& names = schema.columns();
  const py::ssize_t n = static_cast<py::ssize_t>(record.samples.size());
  std::vector<py::array_t<double>> columns;
  for (size_t c = 0; c < names.size(); ++c) columns.emplace_back(n);
  for (py::ssize_t i = 0; i < n; ++i) {
    const Eigen::VectorXd row = schema.Row(record.samples[static_cast<size_t>(i)]);
    for (size_t c = 0; c < names.size(); ++c) columns[c].mutable_at(i) = row[c];
  }
  py::dict table;
  for (size_t c = 0; c < names.size(); ++c) table[py::str(names[c])] = columns[c];
  return table;
}

// Each quantity of the telemetry schema that run()'s result has (TelemetryQuantities), one
// array each, one row a sample, into `result` (and its sub-dicts); kSensors' when `sensed`.
void AddQuantities(const std::vector<TelemetrySample>& samples, bool sensed, py::dict* result) {
  const py::ssize_t n = static_cast<py::ssize_t>(samples.size());
  for (const TelemetryQuantity& q : TelemetryQuantities()) {
    if (q.key == nullptr || (q.part == TelemetryPart::kSensors && !sensed)) continue;
    py::array_t<double> array =
        q.width == 0 ? py::array_t<double>(n) : py::array_t<double>({n, py::ssize_t{q.width}});
    double* out = array.mutable_data();
    const int stride = std::max(1, q.width);
    for (const TelemetrySample& sample : samples) {
      q.fill(sample, out);
      if (q.quaternion) std::rotate(out, out + 1, out + 4);  // RotorPy's [i, j, k, w]
      out += stride;
    }
    if (*q.group == '\0') {
      (*result)[q.key] = array;
      continue;
    }
    if (!result->contains(q.group)) (*result)[q.group] = py::dict();
    (*result)[q.group].cast<py::dict>()[q.key] = array;
  }
}

// run()'s dict (Simulator.run's doc): RotorPy's keys, aerobox's measures, the telemetry.
py::dict Result(const FlightRecord& record, const std::string& status) {
  const std::vector<TelemetrySample>& s = record.samples;
  const FlightResult& f = record.flight;
  const bool sensed = !s.empty() && std::all_of(s.begin(), s.end(), [](const TelemetrySample& r) {
    return r.estimate.has_value();
  });
  py::dict result;
  AddQuantities(s, sensed, &result);
  result["status"] = status;
  result["reached_goal"] = f.status == FlightStatus::kReachedGoal;
  result["collisions"] = f.status == FlightStatus::kCollision ? 1 : 0;
  result["collision_with"] = f.obstacle;
  result["min_clearance"] = f.min_clearance;
  result["tracking_rms"] = f.rms_error;
  result["tracking_max"] = f.max_error;
  result["flight_time"] = f.time;
  result["distance"] = f.distance;
  result["top_speed"] = f.top_speed;
  result["peak_rotor_fraction"] = f.peak_rotor_fraction;
  result["rotor_saturated_time"] = f.saturated_time;
  result["control_rate"] = f.control_rate;
  result["wall_time"] = record.wall_time;
  result["seed"] = static_cast<long long>(record.setup->seed);
  result["max_wind"] = f.max_wind;
  if (sensed) {
    result["estimate_rms"] = f.estimate_rms_error;
    result["estimate_max"] = f.estimate_max_error;
  }
  result["telemetry"] = TelemetryColumns(record);
  return result;
}

// A scenario of several vehicles is flown by aerobox.Swarm (or `aerobox fly`), not as one.
const SetupPtr& OneVehicle(const SetupPtr& setup, const char* who) {
  if (!setup->vehicles.empty()) {
    throw py::value_error(std::string(who) +
                          ": the scenario has several vehicles ([[vehicles]]): " +
                          "fly them with aerobox.Swarm(scenario).run(...) or `aerobox fly`");
  }
  return setup;
}

// run()'s reference: an aerobox Trajectory exactly (its waypoints into `path`), cut at `t_final`
// [s] when that is sooner, or the user's object (PythonReference; `known`: it gave a duration).
Reference RunReference(const py::object& trajectory, double t_final, bool* known,
                       std::vector<Vec3>* path) {
  *known = true;
  if (!py::isinstance<Trajectory>(trajectory)) return PythonReference(trajectory, t_final, known);
  const Trajectory& ours = trajectory.cast<const Trajectory&>();
  Reference reference = ReferenceOf(ours.result.trajectory);
  if (t_final > 0 && t_final < reference.duration) reference.duration = t_final;
  *path = ours.result.waypoints;
  return reference;
}

// run()'s controller at `rate` [Hz]: a built-in by name (`config`'s kind), or the user's object
// (`users` points at it; `config`'s kind names its class).
std::unique_ptr<Controller> RunController(const py::object& controller, const QuadParams& vehicle,
                                          double rate, const std::string& choice,
                                          ControllerConfig* config,
                                          const PythonController** users) {
  config->rate = rate;
  if (py::isinstance<py::str>(controller)) {
    config->kind = controller.cast<std::string>();
    return Checked([&] {
      config->Validate();
      return MakeController(*config, vehicle);
    });
  }
  auto user = std::make_unique<PythonController>(controller, vehicle, ParseCommandChoice(choice));
  *users = user.get();
  config->kind = "python:" + std::string(py::str(py::type::handle_of(controller).attr("__name__")));
  return user;
}

class SimulatorCore {
 public:
  explicit SimulatorCore(SetupPtr setup)
      : setup_(OneVehicle(setup, "aerobox.Simulator")),
        xml_(SceneMjcfFor(*setup_)),
        sim_(Load()),
        obstacles_(setup_->map, CollisionParams{setup_->vehicle.collision_size, 0.0}),
        seed_(setup_->seed) {
    base_.vehicle = &setup_->vehicle;
    base_.inner = setup_->controller.inner;
    Checked([&] { PlaceAtStart(setup_->start); });
  }

  void Reset(long long seed, const py::object& state) {
    if (seed < 0) throw py::value_error("seed must be >= 0");
    seed_ = static_cast<std::uint64_t>(seed);
    sim_ = Load();
    if (state.is_none()) {
      PlaceAtStart(setup_->start);
      return;
    }
    sim_.SetVehicleState(StateFromDict(state));
    sim_.SetRotorThrusts(RotorThrustsFromState(state, setup_->vehicle));
    MakeWorld();
  }

  double Time() const { return world_->time(); }

  // A user's wind, any object with update(t, position) -> (3,) [m/s] (RotorPy's wind profiles),
  // in place of the scenario's [wind], asked before each physics step; None: the scenario's.
  // The world starts anew.
  void SetWindSource(const py::object& wind) {
    base_.wind_source = nullptr;
    if (!wind.is_none()) {
      // the bound method keeps the user's object alive
      base_.wind_source = [update = wind.attr("update")](double t, const Vec3& p_W) {
        return PointFrom(update(t, Vec3Array(p_W)), At("wind.update", t) + ": the wind");
      };
    }
    MakeWorld();
  }

  // The last physics step's accelerations: vdot [m/s^2] (world) and wdot [rad/s^2] (body), as
  // RotorPy's statedot gives them to its IMU.
  py::dict StateDot() const {
    py::dict dot;
    dot["vdot"] = Vec3Array(sim_.LinearAcceleration_W());
    dot["wdot"] = Vec3Array(sim_.AngularAcceleration_B());
    return dot;
  }

  // The true state, with the wind at the vehicle and the rotors' speeds.
  py::dict StateNow() const { return DictOf(world_->Truth()); }

  // The state a controller flies on (as run() gives it to controller.update): the estimate
  // with sensors on, else the truth.
  py::dict SeenNow() const { return DictOf(world_->Seen(world_->Truth())); }

  // `state` as RotorPy's dict, with the wind at the vehicle and the rotors' speeds now.
  py::dict DictOf(const State& state) const {
    const Surroundings now = world_->Now();
    return StateDict(state, now.rotor_thrusts, setup_->vehicle, now.wind_W);
  }

  // `command` held for dt [s]: each physics step as run() makes it, the inner loops on what
  // the vehicle senses, in the same air, with the same sensors.
  py::dict Step(const py::object& command, double dt, const std::string& choice) {
    const double step = world_->step();
    const long steps = std::lround(dt / step);
    if (!(dt > 0) || steps < 1 || std::abs(steps * step - dt) > 1e-9) {
      throw py::value_error("dt " + std::to_string(dt) + " s must be a positive multiple of the " +
                            std::to_string(step) + " s physics step");
    }
    const ControlCommand parsed =
        CommandFromDict(command, ParseCommandChoice(choice), setup_->vehicle, Time(), "step");
    for (long i = 0; i < steps; ++i) {
      const State truth = world_->Truth();
      if (!world_->Command(parsed, world_->Seen(truth))) {
        throw py::value_error("step: the state or the command is not finite");
      }
      world_->Step(truth);
    }
    world_->EndControlPeriod();  // `dt` is the command's control period
    return SeenNow();
  }

  py::list Contacts() const {
    py::list list;
    for (const VehicleContact& c : sim_.VehicleContacts()) list.append(c.other_geom);
    return list;
  }

  py::tuple Run(const py::object& controller, const py::object& trajectory, double t_final,
                double control_rate, const std::string& choice, bool reset,
                const py::object& terminate) {
    if (!(control_rate > 0)) throw py::value_error("control_rate must be positive [Hz]");
    if (!(t_final >= 0) || !std::isfinite(t_final)) {
      throw py::value_error("t_final must be a time >= 0 [s] (0: the trajectory's duration)");
    }
    auto record = std::make_shared<FlightRecord>();
    record->setup = setup_;
    bool duration_known = true;
    const Reference reference =
        RunReference(trajectory, t_final, &duration_known, &record->plan.result.path);
    FlightParams params = setup_->flight;
    if (t_final > 0) params.settle_time = std::max(0.0, t_final - reference.duration);
    const PythonController* users = nullptr;  // the user's controller, when it is one
    ControllerConfig config = setup_->controller;
    const std::unique_ptr<Controller> made =
        RunController(controller, setup_->vehicle, control_rate, choice, &config, &users);
    const Vec3 first = reference.evaluate(0.0, kPosition);
    if (reset) {
      sim_ = Load();
      PlaceAtStart(first);
    }
    record->setup = std::make_shared<FlightSetup>(*setup_);
    record->setup->controller = config;
    record->setup->seed = seed_;

    FlightLoop loop;
    loop.vehicle = &setup_->vehicle;
    loop.controller = made.get();
    record->controller_columns = made->ReportColumns();
    loop.control_rate = control_rate;
    loop.clearance = [this](const Vec3& p) { return obstacles_.Clearance(p); };
    loop.telemetry = [&record](const TelemetrySample& s) { record->samples.push_back(s); };
    Termination termination;
    termination.Into(terminate, trajectory, duration_known, reference, &loop);
    const auto begin = std::chrono::steady_clock::now();
    record->flight = Checked([&] { return FlyTrajectory(reference, params, loop, world_.get()); });
    // the user's exception (or a command that cannot be flown) raised in Python, as it was
    if (users != nullptr) users->RethrowIfFailed();
    if (termination.error) std::rethrow_exception(termination.error);
    record->wall_time =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();

    RecordPlan(reference, first, record.get());
    return py::make_tuple(Result(*record, StatusOf(record->flight, loop)), record);
  }

  py::dict VehicleParams() const { return VehicleDict(setup_->vehicle); }
  double Timestep() const { return world_->step(); }
  const SetupPtr& setup() const { return setup_; }

 private:
  // What was planned, as write_outputs shows it: the waypoints (or the ends) and the trajectory
  // (the user's sampled at the control rate).
  void RecordPlan(const Reference& reference, const Vec3& first, FlightRecord* record) const {
    PlanOutcome& plan = record->plan;
    plan.start.requested = plan.start.used =
        record->samples.empty() ? sim_.VehicleState().p_W : record->samples.front().state.p_W;
    plan.goal.requested = plan.goal.used = reference.evaluate(reference.duration, kPosition);
    if (plan.result.path.empty()) plan.result.path = {first, plan.goal.used};
    plan.result.status = PlanStatus::kSolved;
    plan.planner = "given";
  }

  // The flight's status in words; "completed" for one flown to t_final as asked, with no end
  // to reach (not a failure).
  static std::string StatusOf(const FlightResult& flight, const FlightLoop& loop) {
    if (loop.completion.kind == Completion::Kind::kNever && !loop.terminate &&
        flight.status == FlightStatus::kTimeout) {
      return "completed";
    }
    return ToString(flight.status);
  }

  // a fresh simulation of the scene, at rest at the start
  Simulation Load() const {
    return Checked([&] { return Simulation::FromXml(xml_, setup_->name); });
  }

  // The vehicle at `point` (on the floor when the start is at floor level, else hovering
  // there, its rotors at hover thrust), and the world around it made anew from t = 0.
  void PlaceAtStart(const Vec3& point) {
    PlaceVehicleAtStart(setup_->map, setup_->vehicle, setup_->start, point, &sim_);
    MakeWorld();
  }

  // The air, the sensors and the inner loops, from the simulation as it is now (run()'s and
  // step()'s one world), seeded by seed_.
  void MakeWorld() {
    FlightSetup seeded = *setup_;
    seeded.seed = seed_;
    AddAirAndSensors(seeded, &base_);
    world_ = Checked([&] { return std::make_unique<VehicleWorld>(base_, &sim_); });
  }

  SetupPtr setup_;
  std::string xml_;  // the scene, made once
  Simulation sim_;
  CollisionWorld obstacles_;
  std::uint64_t seed_;
  FlightLoop base_;  // the vehicle, its inner loops, the air and the sensors: the world's
  std::unique_ptr<VehicleWorld> world_;
};

// Several vehicles in one world (aerobox.Swarm): run() flies each vehicle's trajectory with its
// own controller, all at once (FlySwarm), and gives each vehicle's result as Simulator.run does.
class SwarmSimulatorCore {
 public:
  explicit SwarmSimulatorCore(SetupPtr setup) : setup_(std::move(setup)) {
    if (setup_->vehicles.empty()) throw py::value_error("aerobox.Swarm: no vehicles");
    for (size_t i = 0; i < setup_->vehicles.size(); ++i) {
      members_.push_back(setup_->Member(i));
      names_.push_back(setup_->vehicles[i].name);
    }
    xml_ = SceneMjcfFor(*setup_);
  }

  std::vector<std::string> names() const { return names_; }
  py::list VehicleParams() const {
    py::list vehicles;
    for (const FlightSetup& m : members_) vehicles.append(VehicleDict(m.vehicle));
    return vehicles;
  }

  // One controller (a built-in's name or an object with update(t, state, flat_output)) and one
  // trajectory per vehicle, in the vehicles' order.
  py::dict Run(const py::list& controllers, const py::list& trajectories, double t_final,
               double control_rate, const std::string& choice) {
    const size_t n = members_.size();
    if (controllers.size() != n || trajectories.size() != n) {
      throw py::value_error("aerobox.Swarm.run: one controller and one trajectory per vehicle (" +
                            std::to_string(n) + ")");
    }
    if (!(control_rate > 0)) throw py::value_error("control_rate must be positive [Hz]");
    if (!(t_final >= 0) || !std::isfinite(t_final)) {
      throw py::value_error("t_final must be a time >= 0 [s] (0: the trajectories' duration)");
    }
    Simulation sim = Checked([&] { return Simulation::FromXml(xml_, setup_->name, names_); });
    std::vector<Flown> flown(n);
    std::vector<SwarmVehicle> vehicles(n);
    const FlightParams params = setup_->flight;
    for (size_t i = 0; i < n; ++i) {
      Prepare(i, controllers[i], trajectories[i], t_final, control_rate, choice, &sim, &flown[i],
              &vehicles[i]);
      if (t_final > 0) {  // each vehicle's own settle time, to end at t_final
        vehicles[i].flight = params;
        vehicles[i].flight->settle_time = std::max(0.0, t_final - vehicles[i].reference.duration);
      }
    }
    const auto begin = std::chrono::steady_clock::now();
    const SwarmFlightResult result =
        Checked([&] { return FlySwarm(vehicles, params, setup_->swarm, &sim); });
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    py::dict out, each;
    for (size_t i = 0; i < n; ++i) {
      if (flown[i].users) flown[i].users->RethrowIfFailed();
      flown[i].record->flight = result.flights[i];
      flown[i].record->wall_time = wall;
      py::dict r = Result(*flown[i].record, ToString(result.flights[i].status));
      r["min_separation"] = result.vehicle_min_separation[i];
      each[py::str(names_[i])] = r;
    }
    out["vehicles"] = each;
    out["all_reached"] = result.AllReached();
    out["min_separation"] = result.min_separation;
    out["closest_pair"] = result.closest_pair;
    out["flight_time"] = result.time;
    out["wall_time"] = wall;
    return out;
  }

 private:
  struct Flown {
    std::unique_ptr<Controller> controller;
    const PythonController* users = nullptr;
    std::shared_ptr<FlightRecord> record = std::make_shared<FlightRecord>();
    std::unique_ptr<CollisionWorld> obstacles;
  };

  // Vehicle i's controller, reference and loop, the vehicle at the reference's start.
  void Prepare(size_t i, const py::object& controller, const py::object& trajectory, double t_final,
               double control_rate, const std::string& choice, Simulation* sim, Flown* flown,
               SwarmVehicle* v) {
    const FlightSetup& member = members_[i];
    bool known = true;
    std::vector<Vec3> waypoints;
    v->reference = RunReference(trajectory, t_final, &known, &waypoints);
    ControllerConfig config = member.controller;
    flown->controller =
        RunController(controller, member.vehicle, control_rate, choice, &config, &flown->users);
    flown->record->setup = std::make_shared<FlightSetup>(member);
    flown->record->setup->controller = config;
    flown->record->controller_columns = flown->controller->ReportColumns();
    flown->obstacles = std::make_unique<CollisionWorld>(
        setup_->map, CollisionParams{member.vehicle.collision_size, 0.0});
    const Vec3 first = v->reference.evaluate(0.0, kPosition);
    PlaceVehicleAtStart(setup_->map, member.vehicle, member.start, first,
                        &sim->vehicle(static_cast<int>(i)));
    v->name = names_[i];
    FlightSetup seeded = member;
    seeded.seed = setup_->seed + i;
    AddAirAndSensors(seeded, &v->loop);
    v->loop.vehicle = &member.vehicle;
    v->loop.controller = flown->controller.get();
    v->loop.control_rate = control_rate;
    v->loop.inner = member.controller.inner;
    const CollisionWorld* obstacles = flown->obstacles.get();
    v->loop.clearance = [obstacles](const Vec3& p) { return obstacles->Clearance(p); };
    FlightRecord* record = flown->record.get();
    v->loop.telemetry = [record](const TelemetrySample& s) { record->samples.push_back(s); };
    if (!known) v->loop.completion = Termination::OpenEnd(trajectory, v->reference);
    record->plan.start.used = first;
    record->plan.goal.used = v->reference.evaluate(v->reference.duration, kPosition);
    record->plan.result.path = waypoints;  // an aerobox trajectory's, else its ends
    if (waypoints.empty()) record->plan.result.path = {first, record->plan.goal.used};
    record->plan.result.status = PlanStatus::kSolved;
    record->plan.planner = "given";
  }

  SetupPtr setup_;
  std::vector<FlightSetup> members_;
  std::vector<std::string> names_;
  std::string xml_;
};

// What a whole run hands the Python result: the plan, the controller's own columns, every
// control step.
class Recorder : public MissionObserver {
 public:
  explicit Recorder(FlightRecord* record) : record_(record) {}
  void OnPlan(const PlanOutcome& plan) override { record_->plan = plan; }
  void OnFlightStart(const Simulation&, const Controller& controller) override {
    record_->controller_columns = controller.ReportColumns();
  }
  void OnSample(const TelemetrySample& sample) override { record_->samples.push_back(sample); }

 private:
  FlightRecord* record_;
};

py::dict ReplanDict(const ReplanEvent& event) {
  py::dict dict;
  dict["t"] = event.t;
  dict["trigger"] = event.trigger;
  dict["outcome"] = event.outcome;
  dict["planning_time"] = event.planning_time;
  dict["solve_time"] = event.solve_time;
  dict["latency"] = event.latency;
  dict["path_length"] = event.path_length;
  dict["time_capped"] = event.time_capped;
  return dict;
}

// The mission's own keys of aerobox.fly's result: its status, the path, the goals' times, the
// unknown boxes and the replans.
void AddMission(const MissionResult& mission, py::dict* result) {
  py::dict& r = *result;
  r["mission_status"] = ToString(mission.status);
  const std::vector<Vec3>& path = mission.plan.result.path;
  py::array_t<double> waypoints({static_cast<py::ssize_t>(path.size()), py::ssize_t{3}});
  for (size_t i = 0; i < path.size(); ++i) {
    for (int k = 0; k < 3; ++k) waypoints.mutable_at(static_cast<py::ssize_t>(i), k) = path[i][k];
  }
  r["path"] = waypoints;
  r["goal_times"] = mission.flight.goal_times;
  r["unknown_boxes"] = mission.unknown_boxes;
  r["revealed_boxes"] = mission.revealed_boxes;
  r["revealed_at"] = mission.revealed_at;
  r["revealed_distance"] = mission.revealed_distance;
  if (mission.occupancy) {
    // the depth camera's occupancy map at the end: its size and its occupied cells as boxes
    const OccupancyGrid& grid = *mission.occupancy->grid;
    const std::vector<Aabb> occupied = grid.OccupiedBoxes();
    py::dict map;
    map["resolution"] = grid.resolution();
    map["cells"] = grid.cell_count();
    map["occupied"] = grid.occupied_count();
    map["free"] = grid.free_count();
    py::array_t<double> boxes({static_cast<py::ssize_t>(occupied.size()), py::ssize_t{6}});
    for (size_t i = 0; i < occupied.size(); ++i) {
      for (int k = 0; k < 3; ++k) {
        boxes.mutable_at(static_cast<py::ssize_t>(i), k) = occupied[i].min[k];
        boxes.mutable_at(static_cast<py::ssize_t>(i), k + 3) = occupied[i].max[k];
      }
    }
    map["occupied_boxes"] = boxes;
    r["occupancy"] = map;
  }
  py::list replans;
  for (const ReplanEvent& event : mission.replans) replans.append(ReplanDict(event));
  r["replans"] = replans;
}

// aerobox.fly: a whole run as `aerobox fly` flies it (plan, trajectory, scene, flight, with a
// mission's goals, unknown boxes, sensing and replanning), with the set-up's controller or the
// user's object.
py::tuple Fly(const SetupPtr& given, const py::object& controller, const std::string& choice) {
  OneVehicle(given, "aerobox.fly");
  auto record = std::make_shared<FlightRecord>();
  auto setup = std::make_shared<FlightSetup>(*given);
  record->setup = setup;
  std::unique_ptr<PythonController> user;
  MissionParts parts;
  if (!controller.is_none()) {
    user =
        std::make_unique<PythonController>(controller, setup->vehicle, ParseCommandChoice(choice));
    parts.controller = user.get();
    setup->controller.kind =
        "python:" + std::string(py::str(py::type::handle_of(controller).attr("__name__")));
  }
  Recorder recorder(record.get());
  parts.observers = {&recorder};
  const auto begin = std::chrono::steady_clock::now();
  const MissionResult mission = Checked([&] { return RunMission(*given, parts); });
  if (user) user->RethrowIfFailed();
  record->wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  record->flight = mission.flight;
  py::dict result =
      Result(*record, mission.flown ? ToString(mission.flight.status) : ToString(mission.status));
  AddMission(mission, &result);
  return py::make_tuple(result, record);
}

// A built-in controller answering as a Python one does, with every command level at once: its
// own command and what aerobox's inner loops (its own copy, stepped once per call) make of it
// below, down to the rotors.
class BuiltinController {
 public:
  BuiltinController(const SetupPtr& setup, const std::string& kind, double rate)
      : vehicle_(setup->vehicle),
        config_(setup->controller),
        inner_(setup->controller.inner, setup->vehicle) {
    if (!(rate > 0)) throw py::value_error("rate must be positive [Hz]");
    config_.kind = kind;
    config_.rate = rate;
    if (MeasuresAcceleration(config_)) {
      throw py::value_error(
          "builtin_controller: \"" + kind +
          "\" measures the vehicle's acceleration and rotor thrusts, which a state dict does not "
          "carry; fly it by name: Simulator.run(\"" +
          kind + "\", trajectory)");
    }
    controller_ = Checked([&] {
      config_.Validate();
      return MakeController(config_, vehicle_);
    });
  }

  py::dict Update(double t, const py::object& state_dict, const py::object& flat_dict) {
    const State state = StateFromDict(state_dict);
    const FlatOutput flat = FlatFromDict(flat_dict, t, "flat_output");
    ControlCommand command;
    InnerOutput out;
    if (!controller_->Update(t, state, flat, &command) ||
        !inner_.Run(command, state, 1.0 / config_.rate, &out)) {
      throw py::value_error("the built-in controller got a non-finite input");
    }
    py::dict dict;
    dict["cmd_thrust"] = command.thrust;
    const double q[4] = {command.q_WB.x(), command.q_WB.y(), command.q_WB.z(), command.q_WB.w()};
    py::array_t<double> cmd_q(4);
    for (int i = 0; i < 4; ++i) cmd_q.mutable_at(i) = q[i];
    dict["cmd_q"] = cmd_q;
    dict["cmd_w_ff"] = Vec3Array(command.rate_B);
    dict["cmd_w"] = Vec3Array(out.rate_setpoint_B);
    dict["cmd_moment"] = Vec3Array(out.moment_B);
    py::array_t<double> thrusts(4), speeds(4);
    for (int i = 0; i < kNumRotors; ++i) {
      thrusts.mutable_at(i) = out.mixer.thrusts[i];
      speeds.mutable_at(i) = vehicle_.RotorSpeedFor(out.mixer.thrusts[i]);
    }
    dict["cmd_motor_thrusts"] = thrusts;
    dict["cmd_motor_speeds"] = speeds;
    return dict;
  }

 private:
  QuadParams vehicle_;
  ControllerConfig config_;
  InnerLoops inner_;
  std::unique_ptr<Controller> controller_;
};

// The files `aerobox fly` writes, from a run's record: the flight is replayed through the same
// observers (the state of every control step set in a fresh scene).
std::string WriteOutputs(const FlightRecord& record, const std::string& out_dir, bool video,
                         int width, int height, int fps, const std::string& camera, bool report) {
  return Checked([&] {
    const FlightSetup& setup = *record.setup;
    OutputFolder output(out_dir, setup.name);
    const std::string& folder = output.staging();
    output.Run([&] {
      RenderOptions render;
      render.width = width;
      render.height = height;
      render.video = video;
      render.fps = fps;
      try {
        render.camera = ParseCamera(camera);
      } catch (const std::invalid_argument& e) {
        throw py::value_error(std::string("camera: ") + e.what());
      }
      if (width < 16 || height < 16 || (video && (width % 2 || height % 2))) {
        throw py::value_error("size: expected even sides of 16 pixels or more");
      }
      PlanOutcome plan = record.plan;
      if (!plan.trajectory) {
        std::vector<TrajectorySample> samples;
        for (const TelemetrySample& s : record.samples) {
          if (!samples.empty() && s.t <= samples.back().t) continue;
          samples.push_back({s.t, s.setpoint.p_W, s.setpoint.v_W, s.setpoint.a_W});
        }
        TrajectoryResult trajectory;
        trajectory.status = TrajectoryStatus::kSolved;
        if (samples.size() >= 2) trajectory.trajectory = SampledTrajectory(samples);
        MeasureTrajectory(TrajectoryParams(), &trajectory);
        plan.trajectory = trajectory;
      }
      CsvOutputs csv(folder, 1, TelemetryExtrasFor(setup));
      RenderOutputs pictures(folder, setup, render, std::cerr);
      Simulation sim = Simulation::FromXml(SceneMjcfFor(setup), setup.name);
      pictures.OnScene(sim, {});
      ReportOutputs page(folder, setup);
      std::vector<MissionObserver*> observers = {&csv, &pictures};
      if (report) observers.push_back(&page);
      for (MissionObserver* o : observers) o->OnPlan(plan);
      RecordedController controller(record.controller_columns);
      for (MissionObserver* o : observers) o->OnFlightStart(sim, controller);
      for (const TelemetrySample& s : record.samples) {
        sim.SetVehicleState(s.state);
        for (MissionObserver* o : observers) o->OnSample(s);
      }
      for (MissionObserver* o : observers) o->OnFlightEnd(sim, record.flight);
      MissionResult mission;
      mission.plan = plan;
      mission.flown = true;
      mission.flight = record.flight;
      mission.flight_wall_time = record.wall_time;
      mission.status = record.flight.status == FlightStatus::kReachedGoal
                           ? MissionStatus::kReachedGoal
                           : MissionStatus::kFlightFailed;
      const JsonObject summary = RunSummary(setup, mission, {1, pictures.video_frames(), fps});
      WriteFileAtomically((std::filesystem::path(folder) / "summary.json").string(),
                          summary.Text());
      if (report) {
        page.Write(summary.Text(), "# written by the aerobox Python package: Simulator(\"" +
                                       setup.map.source + "\").run(...), seed " +
                                       std::to_string(setup.seed));
      }
    });
    output.Commit();  // the folder holds this run, or (after an error) the one it held
    return output.path();
  });
}

// aerobox.Map's core: a set-up's map, vehicle and endpoints.
void BindSetup(py::module_& m) {
  py::class_<FlightSetup, SetupPtr>(m, "Setup")
      .def_property_readonly("name", [](const FlightSetup& s) { return s.name; })
      .def_property_readonly("map_path", [](const FlightSetup& s) { return s.map.source; })
      .def_property_readonly("start", [](const FlightSetup& s) { return OptionalPoint(s.start); })
      .def_property_readonly("goal", [](const FlightSetup& s) { return OptionalPoint(s.goal); })
      .def_property_readonly("seed", [](const FlightSetup& s) { return s.seed; })
      .def_property_readonly("vehicle_kind", [](const FlightSetup& s) { return s.vehicle_kind; })
      .def_property_readonly("vehicle", [](const FlightSetup& s) { return VehicleDict(s.vehicle); })
      .def_property_readonly("controller", [](const FlightSetup& s) { return s.controller.kind; })
      .def_property_readonly("control_rate", [](const FlightSetup& s) { return s.controller.rate; })
      .def_property_readonly("bounds",
                             [](const FlightSetup& s) {
                               return PointsArray({s.map.bounds.min, s.map.bounds.max});
                             })
      .def_property_readonly("boxes",
                             [](const FlightSetup& s) {
                               py::array_t<double> boxes(
                                   {static_cast<py::ssize_t>(s.map.boxes.size()), py::ssize_t{6}});
                               for (size_t i = 0; i < s.map.boxes.size(); ++i) {
                                 const Aabb& e = s.map.boxes[i].extent;
                                 for (int k = 0; k < 3; ++k) {
                                   boxes.mutable_at(i, k) = e.min[k];
                                   boxes.mutable_at(i, 3 + k) = e.max[k];
                                 }
                               }
                               return boxes;
                             })
      .def_property_readonly("colors",
                             [](const FlightSetup& s) {
                               std::vector<Vec3> rgb;
                               for (const Box& b : s.map.boxes) rgb.push_back(b.rgb);
                               return PointsArray(rgb);
                             })
      .def("world", [](const FlightSetup& s) { return WorldDict(s.map); })
      .def("clearance",
           [](const FlightSetup& s, const py::object& point) {
             const CollisionWorld world(s.map, CollisionParams{s.vehicle.collision_size, 0.0});
             return world.Clearance(PointFrom(point, "point"));
           })
      .def("with_vehicle", &WithVehicle);
}

// Loading a set-up (a file, or a scenario's text with settings) and planning its path.
void BindLoadAndPlan(py::module_& m) {
  m.def(
      "_load",
      [](const std::string& path, const py::object& start, const py::object& goal,
         const py::object& seed) {
        return std::make_shared<FlightSetup>(
            Checked([&] { return LoadFlightSetup(path, Overrides(start, goal, seed)); }));
      },
      py::arg("path"), py::arg("start") = py::none(), py::arg("goal") = py::none(),
      py::arg("seed") = py::none());
  m.def(
      "_from_toml",
      [](const std::string& text, const std::string& label,
         const std::vector<std::tuple<std::string, std::string, std::string>>& settings,
         const std::string& caller) {
        // each (key, TOML value, the Python argument that gave it), named in messages as the
        // argument of `caller`
        SetupOverrides overrides;
        for (const auto& [key, value, argument] : settings) {
          Setting setting;
          setting.key = key;
          setting.value = value;
          setting.where.file = caller;
          setting.option = argument;
          overrides.settings.push_back(std::move(setting));
        }
        return std::make_shared<FlightSetup>(
            Checked([&] { return LoadFlightSetupFromText(text, label, overrides); }));
      },
      py::arg("text"), py::arg("label"), py::arg("settings"), py::arg("caller"));

  m.def("_plan", [](const FlightSetup& setup) {
    // the path only: min_snap() is separate
    const PlanOutcome plan = Checked([&] { return PlanFlight(setup, false); });
    py::dict result;
    result["status"] = ToString(plan.result.status);
    result["path"] = PointsArray(plan.result.path);
    result["planner"] = plan.planner;
    result["planning_time"] = plan.result.stats.planning_time;
    result["iterations"] = plan.result.stats.iterations;
    result["length"] = PathLength(plan.result.path);
    result["start"] = OptionalPoint(plan.start.used);
    result["goal"] = OptionalPoint(plan.goal.used);
    return result;
  });
}

// aerobox.Trajectory's core: a trajectory through given waypoints.
void BindTrajectory(py::module_& m) {
  py::class_<Trajectory>(m, "Trajectory")
      .def_property_readonly("duration",
                             [](const Trajectory& t) { return t.result.trajectory.duration(); })
      .def_property_readonly("status",
                             [](const Trajectory& t) { return ToString(t.result.status); })
      .def_property_readonly(
          "solved",
          [](const Trajectory& t) { return t.result.status == TrajectoryStatus::kSolved; })
      .def_property_readonly("message",
                             [](const Trajectory& t) { return t.result.stats.solver_message; })
      .def_property_readonly("method", [](const Trajectory& t) { return t.method; })
      .def_property_readonly("waypoints",
                             [](const Trajectory& t) { return PointsArray(t.result.waypoints); })
      .def_property_readonly("solve_time",
                             [](const Trajectory& t) { return t.result.stats.solve_time; })
      .def_property_readonly("max_speed",
                             [](const Trajectory& t) { return t.result.stats.max_speed; })
      .def_property_readonly("max_accel",
                             [](const Trajectory& t) { return t.result.stats.max_accel; })
      .def("update", &Trajectory::Update, py::arg("t"));
  m.def("_trajectory", [](const FlightSetup& setup, const py::object& waypoints) {
    const std::vector<Vec3> path = PointsFromArray(waypoints, "waypoints");
    if (path.size() < 2) throw py::value_error("waypoints: two points or more");
    Trajectory t;
    t.method = setup.planning.trajectory_method;
    t.result = Checked([&] { return TrajectoryAlong(setup, path); });
    return t;
  });
}

// Flying: the simulator, the built-in controllers, whole missions and their outputs.
void BindFlight(py::module_& m) {
  py::class_<FlightRecord, std::shared_ptr<FlightRecord>>(m, "FlightRecord")
      .def_property_readonly("samples", [](const FlightRecord& r) { return r.samples.size(); })
      .def_property_readonly("scenario", [](const FlightRecord& r) { return r.setup->name; });

  py::class_<SimulatorCore>(m, "SimulatorCore")
      .def(py::init<SetupPtr>())
      .def("reset", &SimulatorCore::Reset, py::arg("seed"), py::arg("state"))
      .def("step", &SimulatorCore::Step, py::arg("command"), py::arg("dt"), py::arg("command_kind"))
      .def("run", &SimulatorCore::Run, py::arg("controller"), py::arg("trajectory"),
           py::arg("t_final"), py::arg("control_rate"), py::arg("command_kind"), py::arg("reset"),
           py::arg("terminate"))
      .def("contacts", &SimulatorCore::Contacts)
      .def_property_readonly("time", &SimulatorCore::Time)
      .def_property_readonly("state", &SimulatorCore::StateNow)
      .def_property_readonly("seen", &SimulatorCore::SeenNow)
      .def_property_readonly("statedot", &SimulatorCore::StateDot)
      .def("set_wind", &SimulatorCore::SetWindSource, py::arg("wind"))
      .def_property_readonly("vehicle", &SimulatorCore::VehicleParams)
      .def_property_readonly("timestep", &SimulatorCore::Timestep)
      .def_property_readonly("setup", &SimulatorCore::setup);

  py::class_<SwarmSimulatorCore>(m, "SwarmSimulatorCore")
      .def(py::init<SetupPtr>())
      .def("run", &SwarmSimulatorCore::Run, py::arg("controllers"), py::arg("trajectories"),
           py::arg("t_final"), py::arg("control_rate"), py::arg("command_kind"))
      .def_property_readonly("names", &SwarmSimulatorCore::names)
      .def_property_readonly("vehicles", &SwarmSimulatorCore::VehicleParams);

  py::class_<BuiltinController>(m, "BuiltinController")
      .def(py::init<const SetupPtr&, const std::string&, double>(), py::arg("setup"),
           py::arg("kind"), py::arg("rate"))
      .def("update", &BuiltinController::Update, py::arg("t"), py::arg("state"),
           py::arg("flat_output"));

  m.def("_write_outputs", &WriteOutputs, py::arg("record"), py::arg("out_dir"), py::arg("video"),
        py::arg("width"), py::arg("height"), py::arg("fps"), py::arg("camera"), py::arg("report"));
  m.def("_load_class", &LoadClass);
  m.def("_fly", &Fly, py::arg("setup"), py::arg("controller"), py::arg("command_kind"));
}

}  // namespace

PYBIND11_MODULE(_aerobox, m) {
  m.doc() = "aerobox's compiled core; use the package `aerobox`";
  m.attr("__version__") = AEROBOX_VERSION;
  m.attr("mujoco_version") = mj_versionString();
  BindEnvs(m);
  BindSetup(m);
  BindLoadAndPlan(m);
  BindTrajectory(m);
  BindFlight(m);
}

}  // namespace aerobox::python
