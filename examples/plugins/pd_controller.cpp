// An example controller plug-in: PD on position to a thrust vector, commanded as collective
// thrust and attitude (aerobox's inner loops do the rest). Its gains are scenario keys:
//
//   [controller]
//   kind = "example_pd"
//   position_gain = 6.0   # [1/s^2]
//   velocity_gain = 4.0   # [1/s]
//
// It registers itself when aerobox starts; nothing under src/ names it.
#include <cmath>
#include <memory>

#include "common/schema.h"
#include "control/controllers.h"

namespace {

using aerobox::Archive;

struct PdParams {
  double position_gain = 6.0;  // [1/s^2]
  double velocity_gain = 4.0;  // [1/s]

  void Describe(Archive& a) {
    a.Number({"position_gain", "1/s^2", "acceleration asked per metre of position error"},
             &position_gain, 0, 100);
    a.Number({"velocity_gain", "1/s", "acceleration asked per m/s of velocity error"},
             &velocity_gain, 0, 100);
  }
};

class PdController : public aerobox::Controller {
 public:
  PdController(const PdParams& params, double mass) : params_(params), mass_(mass) {}

  aerobox::ControlStatus Update(double, const aerobox::State& state,
                                const aerobox::FlatOutput& setpoint,
                                aerobox::ControlCommand* command) override {
    const aerobox::Vec3 a = params_.position_gain * (setpoint.p_W - state.p_W) +
                            params_.velocity_gain * (setpoint.v_W - state.v_W) + setpoint.a_W +
                            aerobox::Vec3(0, 0, aerobox::kGravity);
    if (!a.allFinite() || !state.q_WB.coeffs().allFinite()) {
      return aerobox::ControlStatus::NonFinite();
    }
    // body z along the force, the yaw the setpoint asks
    const aerobox::Vec3 z = a.normalized();
    const aerobox::Vec3 heading(std::cos(setpoint.yaw), std::sin(setpoint.yaw), 0.0);
    aerobox::Vec3 y = z.cross(heading);
    if (y.norm() < 1e-6) y = z.cross(aerobox::Vec3::UnitX());
    y.normalize();
    aerobox::Mat3 r;
    r << y.cross(z), y, z;
    command->level = aerobox::CommandLevel::kThrustAttitude;
    command->thrust = mass_ * a.dot(state.q_WB * aerobox::Vec3::UnitZ());
    command->q_WB = aerobox::Quat(r);
    command->rate_B = aerobox::Vec3::Zero();
    return aerobox::ControlStatus::Ok();
  }

 private:
  PdParams params_;
  double mass_;
};

[[maybe_unused]] const bool kRegistered = [] {
  aerobox::Controllers().Register(
      "example_pd",
      [](const aerobox::ControllerConfig& config, const aerobox::QuadParams& vehicle) {
        return std::make_unique<PdController>(config.params.Get<PdParams>(), vehicle.mass);
      },
      aerobox::PluginParameters::Of(PdParams()));
  return true;
}();

}  // namespace
