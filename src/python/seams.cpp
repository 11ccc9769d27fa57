#include "python/seams.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include "common/number_format.h"

namespace aerobox::python {
namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

py::array_t<double> VectorArray(const double* values, int n) {
  py::array_t<double> array(n);
  double* out = array.mutable_data();
  for (int i = 0; i < n; ++i) out[i] = values[i];
  return array;
}

// `value` as `n` finite numbers (any array-like of that size, or a number when n == 1).
bool ReadNumbers(py::handle value, int n, double* out, std::string* problem) {
  Array array;
  try {
    array = Array::ensure(value);
  } catch (const py::error_already_set&) {
    array = Array();
  }
  if (!array) {
    PyErr_Clear();
    *problem = "is a " + std::string(py::str(py::type::handle_of(value).attr("__name__"))) +
               ", expected " + (n == 1 ? std::string("a number") : std::to_string(n) + " numbers");
    return false;
  }
  if (array.size() != n) {
    std::ostringstream shape;
    shape << "(";
    for (py::ssize_t d = 0; d < array.ndim(); ++d) shape << (d ? ", " : "") << array.shape(d);
    shape << (array.ndim() == 1 ? ",)" : ")");
    *problem = "has shape " + shape.str() + ", expected " +
               (n == 1 ? std::string("a number") : "(" + std::to_string(n) + ",)");
    return false;
  }
  const double* data = array.data();
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(data[i])) {
      *problem = "is not finite (" + FormatNumber(data[i]) + ")";
      return false;
    }
    out[i] = data[i];
  }
  return true;
}

py::dict AsDict(py::handle value, const std::string& who) {
  if (!py::isinstance<py::dict>(value)) {
    throw py::value_error(who + " returned a " +
                          std::string(py::str(py::type::handle_of(value).attr("__name__"))) +
                          ", expected a dict");
  }
  return py::reinterpret_borrow<py::dict>(value);
}

template <int N>
Eigen::Matrix<double, N, 1> Require(const py::dict& dict, const char* key, const std::string& who) {
  if (!dict.contains(key)) throw py::value_error(who + ": no key '" + key + "'");
  Eigen::Matrix<double, N, 1> value;
  std::string problem;
  if (!ReadNumbers(dict[key], N, value.data(), &problem)) {
    throw py::value_error(who + ": '" + key + "' " + problem);
  }
  return value;
}

double Number(py::handle dict_value, const std::string& what) {
  double value = 0.0;
  std::string problem;
  if (!ReadNumbers(dict_value, 1, &value, &problem)) throw py::value_error(what + " " + problem);
  return value;
}

}  // namespace

std::string At(const std::string& who, double t) {
  return who + " at t = " + FormatNumber(std::round(t * 1e6) / 1e6) + " s";
}

py::array_t<double> Vec3Array(const Vec3& v) { return VectorArray(v.data(), 3); }

Vec3 PointFrom(py::handle value, const std::string& what) {
  Vec3 p;
  std::string problem;
  if (!ReadNumbers(value, 3, p.data(), &problem)) throw py::value_error(what + " " + problem);
  return p;
}

std::vector<Vec3> PointsFromArray(py::handle value, const std::string& what) {
  Array array;
  try {
    array = Array::ensure(value);
  } catch (const py::error_already_set&) {
    array = Array();
  }
  if (!array) PyErr_Clear();
  if (!array || array.ndim() != 2 || array.shape(1) != 3) {
    throw py::value_error(what + ": expected an (N, 3) array of points [m]");
  }
  std::vector<Vec3> points(static_cast<size_t>(array.shape(0)));
  for (size_t i = 0; i < points.size(); ++i) {
    points[i] = Vec3(array.at(i, 0), array.at(i, 1), array.at(i, 2));
    if (!points[i].allFinite()) {
      throw py::value_error(what + ": point " + std::to_string(i) + " is not finite");
    }
  }
  return points;
}

py::object PointsArray(const std::vector<Vec3>& points) {
  py::array_t<double> array({static_cast<py::ssize_t>(points.size()), py::ssize_t{3}});
  auto out = array.mutable_unchecked<2>();
  for (size_t i = 0; i < points.size(); ++i) {
    for (int k = 0; k < 3; ++k) out(i, k) = points[i][k];
  }
  return std::move(array);
}

py::dict StateDict(const State& state, const Vec4& rotor_thrusts, const QuadParams& vehicle,
                   const Vec3& wind_W) {
  py::dict dict;
  dict["x"] = Vec3Array(state.p_W);
  dict["v"] = Vec3Array(state.v_W);
  const double q[4] = {state.q_WB.x(), state.q_WB.y(), state.q_WB.z(), state.q_WB.w()};
  dict["q"] = VectorArray(q, 4);
  dict["w"] = Vec3Array(state.w_B);
  dict["wind"] = Vec3Array(wind_W);
  Vec4 speeds;
  for (int i = 0; i < kNumRotors; ++i) speeds[i] = vehicle.RotorSpeedFor(rotor_thrusts[i]);
  dict["rotor_speeds"] = VectorArray(speeds.data(), 4);
  return dict;
}

State StateFromDict(py::handle value) {
  const py::dict dict = AsDict(value, "state");
  State state;
  const std::string who = "state";
  state.p_W = Require<3>(dict, "x", who);
  if (dict.contains("v")) state.v_W = Require<3>(dict, "v", who);
  if (dict.contains("w")) state.w_B = Require<3>(dict, "w", who);
  if (dict.contains("q")) {
    const Vec4 q = Require<4>(dict, "q", who);
    if (q.norm() < 1e-9) throw py::value_error("state: 'q' is zero, expected [i, j, k, w]");
    state.q_WB = Quat(q[3], q[0], q[1], q[2]).normalized();
  }
  return state;
}

namespace {

// Rotor speeds [rad/s] as thrusts [N], each clipped to the rotors' range first, as RotorPy and
// flightsim do (a negative speed is the slowest, not a thrust of its square).
Vec4 ThrustsAtSpeeds(const Vec4& speeds, const QuadParams& vehicle) {
  const double slowest = vehicle.RotorSpeedFor(vehicle.min_rotor_thrust);
  const double fastest = vehicle.RotorSpeedFor(vehicle.max_rotor_thrust);
  Vec4 thrusts;
  for (int i = 0; i < kNumRotors; ++i) {
    thrusts[i] = vehicle.ThrustAtSpeed(std::clamp(speeds[i], slowest, fastest));
  }
  return thrusts;
}

}  // namespace

Vec4 RotorThrustsFromState(py::handle value, const QuadParams& vehicle) {
  const py::dict dict = AsDict(value, "state");
  if (!dict.contains("rotor_speeds")) return Vec4::Constant(vehicle.HoverThrustPerRotor());
  return ThrustsAtSpeeds(Require<4>(dict, "rotor_speeds", "state"), vehicle);
}

py::dict FlatDict(const FlatOutput& flat) {
  py::dict dict;
  dict["x"] = Vec3Array(flat.p_W);
  dict["x_dot"] = Vec3Array(flat.v_W);
  dict["x_ddot"] = Vec3Array(flat.a_W);
  dict["x_dddot"] = Vec3Array(flat.j_W);
  dict["x_ddddot"] = Vec3Array(flat.s_W);
  dict["yaw"] = flat.yaw;
  dict["yaw_dot"] = flat.yaw_rate;
  return dict;
}

FlatOutput FlatFromDict(py::handle value, double t, const std::string& who) {
  const std::string where = At(who, t);
  const py::dict dict = AsDict(value, where);
  FlatOutput flat;
  flat.p_W = Require<3>(dict, "x", where);
  const auto optional3 = [&](const char* key, Vec3* out) {
    if (dict.contains(key)) *out = Require<3>(dict, key, where);
  };
  optional3("x_dot", &flat.v_W);
  optional3("x_ddot", &flat.a_W);
  optional3("x_dddot", &flat.j_W);
  optional3("x_ddddot", &flat.s_W);
  if (dict.contains("yaw")) flat.yaw = Require<1>(dict, "yaw", where)[0];
  if (dict.contains("yaw_dot")) flat.yaw_rate = Require<1>(dict, "yaw_dot", where)[0];
  return flat;
}

CommandChoice ParseCommandChoice(const std::string& name) {
  static const std::map<std::string, CommandChoice> kChoices = {
      {"auto", CommandChoice::kAuto},
      {"cmd_motor_thrusts", CommandChoice::kMotorThrusts},
      {"cmd_motor_speeds", CommandChoice::kMotorSpeeds},
      {"cmd_ctbm", CommandChoice::kThrustMoment},
      {"cmd_ctbr", CommandChoice::kThrustRates},
      {"cmd_ctatt", CommandChoice::kThrustAttitude}};
  const auto it = kChoices.find(name);
  if (it == kChoices.end()) {
    throw py::value_error("command '" + name +
                          "': expected auto, cmd_motor_thrusts, cmd_motor_speeds, cmd_ctbm "
                          "(thrust + moment), cmd_ctbr (thrust + body rates) or cmd_ctatt "
                          "(thrust + attitude)");
  }
  return it->second;
}

ControlCommand CommandFromDict(py::handle value, CommandChoice choice, const QuadParams& vehicle,
                               double t, const std::string& who) {
  const std::string where = At(who, t);
  const py::dict dict = AsDict(value, where);
  if (choice == CommandChoice::kAuto) {
    if (dict.contains("cmd_motor_thrusts")) {
      choice = CommandChoice::kMotorThrusts;
    } else if (dict.contains("cmd_motor_speeds")) {
      choice = CommandChoice::kMotorSpeeds;
    } else if (dict.contains("cmd_moment")) {
      choice = CommandChoice::kThrustMoment;
    } else if (dict.contains("cmd_w")) {
      choice = CommandChoice::kThrustRates;
    } else if (dict.contains("cmd_q")) {
      choice = CommandChoice::kThrustAttitude;
    } else {
      throw py::value_error(where +
                            ": the dict holds none of cmd_motor_thrusts, cmd_motor_speeds, "
                            "cmd_moment, cmd_w or cmd_q (with cmd_thrust)");
    }
  }
  ControlCommand command;
  switch (choice) {
    case CommandChoice::kMotorThrusts:
      command.level = CommandLevel::kRotorThrusts;
      command.rotor_thrusts = Require<4>(dict, "cmd_motor_thrusts", where);
      break;
    case CommandChoice::kMotorSpeeds: {
      command.level = CommandLevel::kRotorThrusts;
      command.rotor_thrusts = ThrustsAtSpeeds(Require<4>(dict, "cmd_motor_speeds", where), vehicle);
      break;
    }
    case CommandChoice::kThrustMoment:
      command.level = CommandLevel::kThrustMoment;
      command.thrust = Require<1>(dict, "cmd_thrust", where)[0];
      command.moment_B = Require<3>(dict, "cmd_moment", where);
      break;
    case CommandChoice::kThrustRates:
      command.level = CommandLevel::kThrustRates;
      command.thrust = Require<1>(dict, "cmd_thrust", where)[0];
      command.rate_B = Require<3>(dict, "cmd_w", where);
      break;
    case CommandChoice::kThrustAttitude: {
      command.level = CommandLevel::kThrustAttitude;
      command.thrust = Require<1>(dict, "cmd_thrust", where)[0];
      const Vec4 q = Require<4>(dict, "cmd_q", where);
      if (q.norm() < 1e-9)
        throw py::value_error(where + ": 'cmd_q' is zero, expected [i, j, k, w]");
      command.q_WB = Quat(q[3], q[0], q[1], q[2]).normalized();
      // aerobox's own key: body rates [rad/s] added to the attitude loop's (a feed-forward)
      if (dict.contains("cmd_w_ff")) command.rate_B = Require<3>(dict, "cmd_w_ff", where);
      break;
    }
    case CommandChoice::kAuto:
      break;
  }
  return command;
}

namespace {

// A vehicle dict read key by key: which keys were used, and what was added or adjusted.
class DictReader {
 public:
  DictReader(py::handle value, VehicleNotes* notes)
      : dict_(AsDict(value, "vehicle")), notes_(notes) {}
  bool has(const char* key) const { return dict_.contains(key); }
  py::handle operator[](const char* key) {
    used_.insert(key);
    return dict_[key];
  }
  double number(const char* key) {
    return Number((*this)[key], "vehicle['" + std::string(key) + "']");
  }
  double required(const char* key, const char* unit) {
    if (!has(key))
      throw py::value_error(std::string("vehicle: no key '") + key + "' [" + unit + "]");
    return number(key);
  }
  // `key` was absent and aerobox took `value` (with its unit) because `why`
  void Added(const char* key, const std::string& value, const std::string& why) {
    notes_->added.push_back(std::string(key) + " " + value + " (" + why + ")");
  }
  void Adjusted(std::string what) { notes_->adjusted.push_back(std::move(what)); }
  // the keys not used, each with why aerobox has no counterpart
  void ListIgnored() {
    static const std::map<std::string, std::string> kWhy = {
        {"Ixy", "off-diagonal inertia: the body's axes are its principal axes"},
        {"Ixz", "off-diagonal inertia: the body's axes are its principal axes"},
        {"Iyz", "off-diagonal inertia: the body's axes are its principal axes"},
        {"k_h", "translational lift: not modelled"},
        {"k_flap", "blade flapping: not modelled"},
    };
    for (const auto item : dict_) {
      const std::string key = py::str(item.first);
      if (used_.count(key) != 0) continue;
      const auto why = kWhy.find(key);
      // a zero of a term aerobox does not model loses nothing
      if (why != kWhy.end() && IsZero(item.second)) continue;
      notes_->ignored.emplace_back(
          key, why != kWhy.end() ? why->second : "not a vehicle key aerobox reads");
    }
  }

 private:
  static bool IsZero(py::handle value) {
    double x = 0.0;
    std::string problem;
    return ReadNumbers(value, 1, &x, &problem) && x == 0.0;
  }
  py::dict dict_;
  VehicleNotes* notes_;
  std::set<std::string> used_;
};

void ReadInertia(DictReader& d, QuadParams* v) {
  v->mass = d.required("mass", "kg");
  v->inertia =
      Vec3(d.required("Ixx", "kg m^2"), d.required("Iyy", "kg m^2"), d.required("Izz", "kg m^2"));
  // MuJoCo refuses principal moments that break the triangle inequality; a flat vehicle's
  // published values can, by rounding (RotorPy's Crazyflie: Izz 2.89e-5 > 2 x 1.43e-5)
  for (int i = 0; i < 3; ++i) {
    const double others = v->inertia[(i + 1) % 3] + v->inertia[(i + 2) % 3];
    if (v->inertia[i] > others && v->inertia[i] <= 1.05 * others) {
      static const char* const kAxis[] = {"Ixx", "Iyy", "Izz"};
      d.Adjusted(std::string(kAxis[i]) + " " + FormatNumber(v->inertia[i]) + " -> " +
                 FormatNumber(others) +
                 " kg m^2 (MuJoCo needs each moment at most the sum of the others)");
      v->inertia[i] = others;
    }
  }
}

// Thrust and yaw coefficients (RotorPy's k_eta, k_m, or flightsim's k_thrust, k_drag) and the
// rotor speed range.
void ReadRotors(DictReader& d, QuadParams* v) {
  if (d.has("num_rotors") && d.number("num_rotors") != kNumRotors) {
    throw py::value_error("vehicle['num_rotors']: aerobox flies quadrotors (4 rotors)");
  }
  const char* k_thrust = d.has("k_eta") ? "k_eta" : "k_thrust";
  const char* k_moment = d.has("k_m") ? "k_m" : "k_drag";
  if (!d.has(k_thrust)) throw py::value_error("vehicle: no key 'k_eta' [N/(rad/s)^2]");
  if (!d.has(k_moment)) throw py::value_error("vehicle: no key 'k_m' [N m/(rad/s)^2]");
  v->thrust_coefficient = d.number(k_thrust);
  if (!(v->thrust_coefficient > 0)) {
    throw py::value_error(std::string("vehicle['") + k_thrust + "'] must be positive");
  }
  v->yaw_moment_per_thrust = d.number(k_moment) / v->thrust_coefficient;
  v->max_rotor_thrust = v->ThrustAtSpeed(d.required("rotor_speed_max", "rad/s"));
  if (d.has("rotor_speed_min")) {
    v->min_rotor_thrust = v->ThrustAtSpeed(d.number("rotor_speed_min"));
  } else {
    v->min_rotor_thrust = 0.0;
    d.Added("rotor_speed_min", "0 rad/s", "the rotors may stop");
  }
}

// The motor lag: RotorPy's tau_m (one per rotor; MuJoCo's filter here has one for all: their
// mean). flightsim's vehicle has none: its rotors follow the command after one physics step.
void ReadMotorLag(DictReader& d, bool flightsim, double step, QuadParams* v) {
  if (!d.has("tau_m")) {
    if (flightsim) {
      v->motor_time_constant = step;
      d.Added("tau_m", FormatNumber(step) + " s",
              "flightsim's vehicle has no motor lag: the thrust follows the command after one "
              "physics step");
    } else {
      d.Added("tau_m", FormatNumber(v->motor_time_constant) + " s",
              "aerobox's default motor lag: the dict gives none");
    }
    return;
  }
  Array taus = Array::ensure(d["tau_m"]);
  if (!taus || taus.size() < 1) {
    PyErr_Clear();
    throw py::value_error("vehicle['tau_m']: expected a time constant [s] or one per rotor");
  }
  double sum = 0.0;
  for (py::ssize_t i = 0; i < taus.size(); ++i) sum += taus.data()[i];
  const double mean = sum / static_cast<double>(taus.size());
  v->motor_time_constant = std::max(mean, step);
  if (mean < step) {
    d.Adjusted("tau_m " + FormatNumber(mean) + " -> " + FormatNumber(step) +
               " s (the physics step: no lag is shorter)");
  }
}

// RotorPy's motor_noise_std: it adds N(0, sigma^2) to the rotor speeds after each simulation
// step (its magnitude: RotorPy takes np.abs); aerobox once per control period, the same when
// the controller runs at RotorPy's sim_rate.
void ReadMotorNoise(DictReader& d, QuadParams* v) {
  if (!d.has("motor_noise_std")) return;
  v->motor_noise = std::abs(d.number("motor_noise_std"));
  if (v->motor_noise > 0) {
    d.Adjusted("motor_noise_std " + FormatNumber(v->motor_noise) +
               " rad/s -> added to each rotor's speed once per control period (RotorPy adds it "
               "once per simulation step: the same when the controller runs at its sim_rate)");
  }
}

// Where the rotors are, in the dict's order (RotorPy's Multirotor iterates rotor_pos so too),
// never reordered: rotor i of the commands is the i-th entry the user gave. flightsim's
// arm_length: a "+" with rotors on +x, +y, -x, -y.
void ReadLayout(DictReader& d, QuadParams* v) {
  std::vector<Vec3> positions;
  if (d.has("rotor_pos")) {
    const py::handle rotor_pos = d["rotor_pos"];
    if (py::isinstance<py::dict>(rotor_pos)) {
      for (const auto item : py::reinterpret_borrow<py::dict>(rotor_pos)) {
        positions.push_back(PointFrom(
            item.second, "vehicle['rotor_pos']['" + std::string(py::str(item.first)) + "']"));
      }
    } else {
      positions = PointsFromArray(rotor_pos, "vehicle['rotor_pos']");
    }
  } else if (d.has("arm_length")) {
    const double l = d.number("arm_length");
    positions = {Vec3(l, 0, 0), Vec3(0, l, 0), Vec3(-l, 0, 0), Vec3(0, -l, 0)};
  } else {
    throw py::value_error("vehicle: no key 'rotor_pos' (or 'arm_length') [m]");
  }
  if (positions.size() != kNumRotors) {
    throw py::value_error("vehicle['rotor_pos']: expected 4 rotors, got " +
                          std::to_string(positions.size()));
  }
  for (int i = 0; i < kNumRotors; ++i) v->rotor_positions_B[i] = positions[i];
  if (d.has("rotor_directions")) {
    Vec4 directions;
    std::string problem;
    if (!ReadNumbers(d["rotor_directions"], 4, directions.data(), &problem)) {
      throw py::value_error("vehicle: 'rotor_directions' " + problem);
    }
    for (int i = 0; i < kNumRotors; ++i) {
      if (std::abs(std::abs(directions[i]) - 1.0) > 1e-9) {
        throw py::value_error("vehicle['rotor_directions']: expected +1 or -1 per rotor");
      }
      v->rotor_directions[i] = directions[i] > 0 ? 1 : -1;
    }
  } else {
    v->rotor_directions = {+1, -1, +1, -1};
    d.Added("rotor_directions", "[+1, -1, +1, -1]",
            "flightsim's yaw signs: rotors 1 and 3 give a positive yaw reaction");
  }
  // the collision box covers the rotor discs; its height is the Crazyflie's (29 mm)
  double reach = 0.0;
  for (const Vec3& r : v->rotor_positions_B) {
    reach = std::max({reach, std::abs(r.x()), std::abs(r.y())});
  }
  double radius = 0.3 * reach;
  if (d.has("rotor_radius")) {
    radius = d.number("rotor_radius");
  } else {
    d.Added("rotor_radius", FormatNumber(radius) + " m", "0.3 of the arm, for the collision box");
  }
  v->propeller_radius = radius;
  v->guard_radius = 1.05 * radius;
  v->collision_size = Vec3(2 * (reach + radius), 2 * (reach + radius), 0.03);
}

// RotorPy's drag: its parasitic drag -|v| diag(c_Dx, c_Dy, c_Dz) v is aerobox's body drag, term
// for term. Its rotor drag grows with the rotor's speed (-w_i diag(k_d, k_d, k_z) v_i),
// aerobox's with its thrust (-T_i diag(k) v_i): they are set equal at hover.
void ReadDrag(DictReader& d, QuadParams* v) {
  const char* body[] = {"c_Dx", "c_Dy", "c_Dz"};
  for (int i = 0; i < 3; ++i) {
    if (d.has(body[i])) v->body_drag[i] = d.number(body[i]);
  }
  if (!d.has("k_d") && !d.has("k_z")) return;
  const double hover_speed = v->RotorSpeedFor(v->HoverThrustPerRotor());
  const double k_d = d.has("k_d") ? d.number("k_d") : 0.0;
  const double k_z = d.has("k_z") ? d.number("k_z") : 0.0;
  const double per_newton = 1.0 / (v->thrust_coefficient * hover_speed);
  v->rotor_drag = Vec3(k_d, k_d, k_z) * per_newton;
  char text[200];
  std::snprintf(text, sizeof(text),
                "k_d, k_z -> rotor drag %.3g, %.3g s/m per newton of thrust (RotorPy's rotor "
                "drag grows with the rotor's speed, aerobox's with its thrust: equal at hover, "
                "%.0f rad/s)",
                v->rotor_drag.x(), v->rotor_drag.z(), hover_speed);
  d.Adjusted(text);
}

}  // namespace

QuadParams VehicleFromDict(py::handle value, double physics_step, VehicleNotes* notes) {
  DictReader d(value, notes);
  // flightsim's dict: its "+" layout from arm_length, its k_thrust and k_drag, no motor lag
  const bool flightsim = !d.has("rotor_pos") && d.has("arm_length");
  QuadParams v;
  ReadInertia(d, &v);
  ReadRotors(d, &v);
  ReadMotorLag(d, flightsim, physics_step, &v);
  ReadMotorNoise(d, &v);
  ReadLayout(d, &v);
  ReadDrag(d, &v);
  d.ListIgnored();
  try {
    v.Validate();
  } catch (const std::invalid_argument& e) {
    throw py::value_error(std::string("vehicle: ") + e.what());
  }
  return v;
}

py::dict VehicleDict(const QuadParams& v) {
  py::dict dict;
  dict["mass"] = v.mass;
  dict["Ixx"] = v.inertia.x();
  dict["Iyy"] = v.inertia.y();
  dict["Izz"] = v.inertia.z();
  dict["Ixy"] = 0.0;
  dict["Ixz"] = 0.0;
  dict["Iyz"] = 0.0;
  dict["num_rotors"] = kNumRotors;
  py::dict rotor_pos;
  for (int i = 0; i < kNumRotors; ++i) {
    rotor_pos[py::str("r" + std::to_string(i + 1))] = Vec3Array(v.rotor_positions_B[i]);
  }
  dict["rotor_pos"] = rotor_pos;
  const double directions[4] = {double(v.rotor_directions[0]), double(v.rotor_directions[1]),
                                double(v.rotor_directions[2]), double(v.rotor_directions[3])};
  dict["rotor_directions"] = VectorArray(directions, 4);
  dict["rotor_radius"] = v.propeller_radius;
  dict["k_eta"] = v.thrust_coefficient;
  dict["k_m"] = v.yaw_moment_per_thrust * v.thrust_coefficient;
  dict["rotor_speed_min"] = v.RotorSpeedFor(v.min_rotor_thrust);
  dict["rotor_speed_max"] = v.RotorSpeedFor(v.max_rotor_thrust);
  dict["tau_m"] = VectorArray(Vec4::Constant(v.motor_time_constant).eval().data(), 4);
  dict["motor_noise_std"] = v.motor_noise;
  return dict;
}

py::dict WorldDict(const Map& map) {
  const auto extents = [](const Aabb& box) {
    py::list list;
    for (int i = 0; i < 3; ++i) {
      list.append(box.min[i]);
      list.append(box.max[i]);
    }
    return list;
  };
  py::dict bounds;
  bounds["extents"] = extents(map.bounds);
  py::list blocks;
  for (const Box& box : map.boxes) {
    py::dict block;
    block["extents"] = extents(box.extent);
    block["color"] = py::make_tuple(box.rgb.x(), box.rgb.y(), box.rgb.z());
    block["name"] = box.name;
    blocks.append(block);
  }
  py::dict world;
  world["bounds"] = bounds;
  world["blocks"] = blocks;
  return world;
}

PythonController::PythonController(py::object controller, const QuadParams& vehicle,
                                   CommandChoice choice)
    : vehicle_(vehicle), choice_(choice) {
  if (!py::hasattr(controller, "update")) {
    throw py::value_error("the controller has no update(t, state, flat_output) method");
  }
  update_ = controller.attr("update");
}

std::string DescribeError(const py::error_already_set& error) {
  std::string text = py::str(error.type().attr("__name__")).cast<std::string>() + ": " +
                     py::str(error.value()).cast<std::string>();
  // a syntax error names the user's file and line itself; its traceback ends in the importer
  if (error.matches(PyExc_SyntaxError)) return text;
  // where it was raised: the innermost frame of the user's code (not the interpreter's own
  // frozen modules)
  py::object at;
  for (py::object frame = py::reinterpret_borrow<py::object>(error.trace());
       frame && !frame.is_none(); frame = frame.attr("tb_next")) {
    const std::string file = py::str(frame.attr("tb_frame").attr("f_code").attr("co_filename"));
    if (file.rfind("<frozen ", 0) != 0) at = frame;
  }
  if (!at) return text;
  const py::object code = at.attr("tb_frame").attr("f_code");
  const std::string file = py::str(code.attr("co_filename"));
  return text + " (" + file.substr(file.rfind('/') + 1) + " line " +
         std::to_string(at.attr("tb_lineno").cast<int>()) + ", in " +
         py::str(code.attr("co_name")).cast<std::string>() + ")";
}

std::string FormatTraceback(const py::error_already_set& error) {
  try {
    const py::object lines =
        py::module_::import("traceback")
            .attr("format_exception")(error.type(), error.value(), error.trace());
    std::string text = py::str("").attr("join")(lines).cast<std::string>();
    while (!text.empty() && text.back() == '\n') text.pop_back();
    return text;
  } catch (const std::exception&) {
    return "";
  }
}

ControlStatus PythonController::Update(double t, const State& state, const FlatOutput& setpoint,
                                       ControlCommand* command) {
  const std::string who = "controller.update";
  try {
    const py::object answer =
        update_(t, StateDict(state, now_.rotor_thrusts, vehicle_, now_.wind_W), FlatDict(setpoint));
    *command = CommandFromDict(answer, choice_, vehicle_, t, who);
  } catch (py::error_already_set& e) {
    ControlStatus failed =
        ControlStatus::Failed(At(who, t) + ": " + DescribeError(e), FormatTraceback(e));
    // the user's own exception, with where it happened (Python 3.11's notes)
    if (py::hasattr(e.value(), "add_note")) {
      e.value().attr("add_note")("aerobox: raised by " + At(who, t));
    }
    error_ = std::current_exception();
    return failed;
  } catch (const std::exception& e) {
    // a command that cannot be flown: the message names the call, the time and the key
    error_ = std::current_exception();
    return ControlStatus::Failed(e.what());
  }
  return ControlStatus::Ok();
}

void PythonController::RethrowIfFailed() const {
  if (error_) std::rethrow_exception(error_);
}

Reference PythonReference(py::object trajectory, double t_final, bool* duration_known) {
  if (!py::hasattr(trajectory, "update")) {
    throw py::value_error("the trajectory has no update(t) method");
  }
  double duration = 0.0;
  *duration_known = false;
  for (const char* key : {"duration", "t_final"}) {
    if (py::hasattr(trajectory, key) && !trajectory.attr(key).is_none()) {
      duration = Number(trajectory.attr(key), std::string("trajectory.") + key);
      *duration_known = true;
      break;
    }
  }
  if (t_final > 0 && (!*duration_known || t_final < duration)) duration = t_final;
  if (!(duration > 0) && !(t_final > 0)) {
    throw py::value_error(
        "the trajectory has no duration: give it a duration [s] attribute or pass t_final");
  }
  struct Cache {
    py::object update;
    double t = std::numeric_limits<double>::quiet_NaN();
    FlatOutput flat;
    const FlatOutput& At(double time) {
      if (!(time == t)) {
        flat = FlatFromDict(update(time), time, "trajectory.update");
        t = time;
      }
      return flat;
    }
  };
  auto cache = std::make_shared<Cache>();
  cache->update = trajectory.attr("update");
  Reference reference;
  reference.duration = duration;
  reference.evaluate = [cache](double t, int derivative) -> Vec3 {
    const FlatOutput& flat = cache->At(t);
    switch (derivative) {
      case 0:
        return flat.p_W;
      case 1:
        return flat.v_W;
      case 2:
        return flat.a_W;
      case 3:
        return flat.j_W;
      default:
        return flat.s_W;
    }
  };
  reference.heading = [cache](double t) {
    const FlatOutput& flat = cache->At(t);
    return std::make_pair(flat.yaw, flat.yaw_rate);
  };
  return reference;
}

PythonPlanner::PythonPlanner(py::object planner, py::dict world, const PlannerContext& context)
    : planner_(std::move(planner)), world_(std::move(world)), context_(context) {
  if (!py::hasattr(planner_, "plan")) {
    throw py::value_error("the planner has no plan(world, start, goal) method");
  }
}

PlanResult PythonPlanner::Plan(const Vec3& start, const Vec3& goal) {
  PlanResult result;
  const auto begin = std::chrono::steady_clock::now();
  if (!context_.validity.state(start)) {
    result.status = PlanStatus::kStartInvalid;
    return result;
  }
  if (!context_.validity.state(goal)) {
    result.status = PlanStatus::kGoalInvalid;
    return result;
  }
  const py::object answer = planner_.attr("plan")(world_, Vec3Array(start), Vec3Array(goal));
  result.stats.planning_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  if (answer.is_none()) {
    result.status = PlanStatus::kNoPathWithinBudget;
    return result;
  }
  std::vector<Vec3> path = PointsFromArray(answer, "planner.plan");
  if (path.size() < 2) throw py::value_error("planner.plan: a path needs two points or more");
  // the path goes from the start to the goal, each leg free
  if ((path.front() - start).norm() > 1e-6) path.insert(path.begin(), start);
  if ((path.back() - goal).norm() > 1e-6) path.push_back(goal);
  const double planning_time = result.stats.planning_time;
  result = CheckGivenPath(std::move(path), context_.validity);
  result.stats.planning_time = planning_time;
  return result;
}

PythonGenerator::PythonGenerator(py::object cls, double rate)
    : class_(std::move(cls)), rate_(rate) {}

TrajectoryResult PythonGenerator::Generate(const std::vector<Vec3>& path,
                                           const TrajectoryWorld& world) {
  const auto begin = std::chrono::steady_clock::now();
  const py::object trajectory = class_(PointsArray(path));
  bool known = false;
  const Reference reference = PythonReference(trajectory, 0.0, &known);
  std::vector<TrajectorySample> samples;
  const long n = std::max(1L, std::lround(reference.duration * rate_));
  for (long i = 0; i <= n; ++i) {
    const double t = reference.duration * static_cast<double>(i) / static_cast<double>(n);
    samples.push_back(
        {t, reference.evaluate(t, 0), reference.evaluate(t, 1), reference.evaluate(t, 2)});
  }
  TrajectoryResult result;
  result.trajectory = SampledTrajectory(samples);
  result.waypoints = path;
  result.stats.segments = static_cast<int>(n);
  result.status = TrajectoryStatus::kSolved;
  for (size_t i = 1; i < samples.size(); ++i) {
    if (world.segment_free && !world.segment_free(samples[i - 1].p_W, samples[i].p_W)) {
      result.status = TrajectoryStatus::kCollides;
      result.stats.solver_message =
          "the Python trajectory leaves free space at t = " + FormatNumber(samples[i].t) + " s";
      break;
    }
  }
  if (result.status == TrajectoryStatus::kSolved) result.stats.solver_message = "Python";
  MeasureTrajectory(TrajectoryParams(), &result);
  result.stats.solve_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  return result;
}

py::object LoadClass(const std::string& spec) {
  const size_t colon = spec.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == spec.size()) {
    throw py::value_error("'" + spec + "': expected file.py:ClassName");
  }
  const std::filesystem::path file = std::filesystem::absolute(spec.substr(0, colon));
  const std::string class_name = spec.substr(colon + 1);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw py::value_error("'" + file.string() + "': no such Python file");
  }
  const py::module_ util = py::module_::import("importlib.util");
  const std::string module_name = "aerobox_user_" + file.stem().string();
  const py::object module_spec = util.attr("spec_from_file_location")(module_name, file.string());
  const py::object module = util.attr("module_from_spec")(module_spec);
  py::module_::import("sys").attr("modules")[py::str(module_name)] = module;
  // the file's own folder first, so that its sibling modules import
  py::list sys_path = py::module_::import("sys").attr("path");
  if (!sys_path.contains(file.parent_path().string()))
    sys_path.insert(0, file.parent_path().string());
  module_spec.attr("loader").attr("exec_module")(module);
  if (!py::hasattr(module, class_name.c_str())) {
    throw py::value_error("'" + file.string() + "' has no class '" + class_name + "'");
  }
  return module.attr(class_name.c_str());
}

}  // namespace aerobox::python
