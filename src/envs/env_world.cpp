#include "envs/env_world.h"

#include <cmath>
#include <stdexcept>

#include "common/seed.h"

namespace aerobox {
namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

EnvWorld::EnvWorld(const EnvParams& params, Simulation sim)
    : params_(params),
      vehicle_(params.Vehicle()),
      sim_(std::move(sim)),
      steps_per_control_(std::lround(1.0 / (params.control_rate * sim_.timestep()))),
      rng_(StreamSeed(1, SeedStream::kEnvironment)) {
  params_.Validate();
  level_ = params.action == "thrusts" ? CommandLevel::kRotorThrusts
           : params.action == "ctbm"  ? CommandLevel::kThrustMoment
           : params.action == "ctbr"  ? CommandLevel::kThrustRates
                                      : CommandLevel::kThrustAttitude;
  loop_.vehicle = &vehicle_;
  loop_.control_rate = params.control_rate;
  loop_.inner = ControllerConfig().inner;
}

double EnvWorld::Uniform() { return static_cast<double>(rng_() >> 11) * 0x1.0p-53; }

// Uniform in the ball of `radius` [m or m/s or rad/s]: a direction from three normal draws (Box
// and Muller), a distance from the cube root.
Vec3 EnvWorld::InBall(double radius) {
  Vec3 d;
  for (int i = 0; i < 3; ++i) {
    const double u = 1.0 - Uniform(), v = Uniform();
    d[i] = std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * kPi * v);
  }
  const double n = d.norm();
  if (n < 1e-12) return Vec3::Zero();
  return d / n * (radius * std::cbrt(Uniform()));
}

State EnvWorld::RandomStart() {
  State s;
  s.p_W = params_.target + InBall(params_.start_radius);
  s.v_W = InBall(params_.start_speed);
  const double yaw = 2.0 * kPi * Uniform() - kPi;
  const double axis = 2.0 * kPi * Uniform();
  const double tilt = params_.start_tilt * Uniform();
  s.q_WB = Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ())) *
           Quat(Eigen::AngleAxisd(tilt, Vec3(std::cos(axis), std::sin(axis), 0.0)));
  s.w_B = InBall(params_.start_rate);
  return s;
}

void EnvWorld::Reset(std::optional<std::uint64_t> seed, float* observation) {
  if (seed) rng_.seed(StreamSeed(*seed, SeedStream::kEnvironment));
  sim_.ResetData();
  sim_.SetVehicleState(RandomStart());
  sim_.SetRotorThrusts(Vec4::Constant(vehicle_.HoverThrustPerRotor()));
  loop_.seed = rng_();
  world_.emplace(loop_, &sim_);
  t_ = 0.0;
  state_ = sim_.VehicleState();
  last_action_.fill(0.0);
  Observe(observation);
}

ControlCommand EnvWorld::CommandOf(const double* a) const {
  const double low = vehicle_.MinRotorThrust(), high = vehicle_.MaxRotorThrust();
  const auto rotor = [&](double x) { return low + 0.5 * (x + 1.0) * (high - low); };
  ControlCommand c;
  c.level = level_;
  c.thrust = 4.0 * rotor(a[0]);
  if (level_ == CommandLevel::kRotorThrusts) {
    for (int i = 0; i < 4; ++i) c.rotor_thrusts[i] = rotor(a[i]);
  } else if (level_ == CommandLevel::kThrustMoment) {
    const double roll_pitch = high * vehicle_.ArmLength();
    const double yaw = 2.0 * high * vehicle_.yaw_moment_per_thrust;
    c.moment_B = Vec3(a[1] * roll_pitch, a[2] * roll_pitch, a[3] * yaw);
  } else if (level_ == CommandLevel::kThrustRates) {
    c.rate_B = Vec3(a[1], a[2], a[3]) * params_.max_rate;
  } else {
    c.q_WB = Quat(Eigen::AngleAxisd(a[3] * kPi, Vec3::UnitZ())) *
             Quat(Eigen::AngleAxisd(a[2] * params_.max_tilt, Vec3::UnitY())) *
             Quat(Eigen::AngleAxisd(a[1] * params_.max_tilt, Vec3::UnitX()));
  }
  return c;
}

EnvStep EnvWorld::Step(const double* action, float* observation) {
  const ControlCommand command = CommandOf(action);
  EnvStep out;
  bool touched = false;
  State truth = world_->Truth();
  for (long k = 0; k < steps_per_control_ && !touched; ++k) {
    world_->Command(command, truth);
    truth = world_->Step(truth);
    touched = sim_.VehicleTouches();
  }
  world_->EndControlPeriod();
  t_ += 1.0 / params_.control_rate;
  state_ = world_->Truth();
  const bool finite = state_.AllFinite();
  const double distance = (state_.p_W - params_.target).norm();
  out.terminated =
      touched || !finite || !(distance <= params_.bounds_radius) || !sim_.TakeNewWarnings().empty();
  out.truncated = !out.terminated && t_ >= params_.episode_time - 1e-9;
  double squared = 0.0;
  for (int i = 0; i < 4; ++i) {
    last_action_[i] = action[i];
    squared += action[i] * action[i];
  }
  if (finite) {
    out.terms = {params_.reward_alive, -params_.reward_position * distance,
                 -params_.reward_velocity * state_.v_W.norm(),
                 -params_.reward_rate * state_.w_B.norm(), -params_.reward_action * squared};
  }
  for (double term : out.terms) out.reward += term;
  Observe(observation);
  return out;
}

void EnvWorld::Observe(float* o) const {
  const State& s = state_;
  const Vec3 d = s.p_W - params_.target;
  int n = 0;
  for (int i = 0; i < 3; ++i) o[n++] = static_cast<float>(d[i]);
  for (int i = 0; i < 3; ++i) o[n++] = static_cast<float>(s.v_W[i]);
  if (params_.attitude == "matrix") {
    const Mat3 R = s.q_WB.toRotationMatrix();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) o[n++] = static_cast<float>(R(r, c));
    }
  } else {
    const double sign = s.q_WB.w() < 0 ? -1.0 : 1.0;
    for (double q : {s.q_WB.w(), s.q_WB.x(), s.q_WB.y(), s.q_WB.z()}) {
      o[n++] = static_cast<float>(sign * q);
    }
  }
  for (int i = 0; i < 3; ++i) o[n++] = static_cast<float>(s.w_B[i]);
  for (double a : last_action_) o[n++] = static_cast<float>(a);
}

}  // namespace aerobox
