// The controller seam: what the vehicle's controller sees and what it may command. A controller
// is called at its own rate with the state and the trajectory's flat outputs, and answers with
// a command at any of RotorPy's control abstractions; aerobox runs the inner loops below that
// command (control/inner_loops.h) at the physics rate. The built-ins (controllers.h) are
// ordinary implementations; a user's controller is one more.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "common/flat_output.h"
#include "common/state.h"
#include "common/types.h"

namespace aerobox {

// How far down the cascade a command reaches.
enum class CommandLevel {
  kRotorThrusts,    // four rotor thrusts [N] (RotorPy's cmd_motor_thrusts)
  kThrustMoment,    // collective thrust [N] and body moments [N m] (cmd_ctbm)
  kThrustRates,     // collective thrust [N] and body rates [rad/s] (cmd_ctbr)
  kThrustAttitude,  // collective thrust [N] and attitude (cmd_ctatt)
};
const char* ToString(CommandLevel level);

struct ControlCommand {
  CommandLevel level = CommandLevel::kThrustAttitude;
  Vec4 rotor_thrusts = Vec4::Zero();  // [N], rotor order of vehicle/quad_params.h
  double thrust = 0.0;                // collective thrust along the body's z [N]
  Vec3 moment_B = Vec3::Zero();       // body moments [N m]
  // body rates [rad/s]; with kThrustAttitude, a feed-forward added to what the attitude loop
  // asks (zero: none)
  Vec3 rate_B = Vec3::Zero();
  Quat q_WB = Quat::Identity();  // attitude, body to world
};

// What came of one control step: a command, or why there is none. A flight ends at the first
// step without a command: as non-finite (FlightStatus::kNonFinite) or as the controller's
// failure (FlightStatus::kControllerFailed, with the message and the detail).
struct ControlStatus {
  enum class Code {
    kOk,
    kNonFinite,  // an input (the state or the setpoint) was not finite
    kFailed,     // the controller itself failed: an error in a user's controller
  };
  Code code = Code::kOk;
  std::string message;  // kFailed: what went wrong, and at what time, on one line
  std::string detail;   // kFailed: more, when there is (a Python controller's traceback)

  static ControlStatus Ok() { return {}; }
  static ControlStatus NonFinite() { return {Code::kNonFinite, "", ""}; }
  static ControlStatus Failed(std::string message, std::string detail = "") {
    return {Code::kFailed, std::move(message), std::move(detail)};
  }
  bool ok() const { return code == Code::kOk; }
  explicit operator bool() const { return ok(); }
};

// What a controller may know besides the state, given before each Update: the wind at the
// vehicle [m/s] (world ENU) over the last physics step and the rotors' thrusts [N] now (RotorPy's
// state['wind'] and state['rotor_speeds']), and the vehicle's measured acceleration [m/s^2]
// (world ENU, gravity not included): with sensors on the IMU's (its specific force less the
// estimated bias, turned by the estimated attitude), else the physics' own, and `imu` says
// which. INDI and the disturbance observer read the acceleration and the thrusts.
struct Surroundings {
  Vec3 wind_W = Vec3::Zero();
  Vec4 rotor_thrusts = Vec4::Zero();
  Vec3 acceleration_W = Vec3::Zero();
  bool imu = false;
};

class Controller {
 public:
  virtual ~Controller() = default;

  // Before each Update (see Surroundings).
  virtual void Sense(const Surroundings& /*now*/) {}

  // One control step at flight time t [s]: the state (ENU world, FLU body) and the setpoint in,
  // the command out. Never throws: an input that is not finite, or an error of the controller's
  // own (a user's exception), comes back as the status.
  virtual ControlStatus Update(double t, const State& state, const FlatOutput& setpoint,
                               ControlCommand* command) = 0;

  // Telemetry columns of the controller's own (names with their unit in the README or the
  // controller's header), and their values after the last Update, in that order.
  virtual std::vector<std::string> ReportColumns() const { return {}; }
  virtual void Report(std::vector<double>* values) const { values->clear(); }
};

}  // namespace aerobox
