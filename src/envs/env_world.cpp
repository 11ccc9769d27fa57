#include "envs/env_world.h"

#include <cmath>
#include <stdexcept>

#include "common/seed.h"

namespace aerobox {
namespace {

constexpr double kPi = 3.14159265358979323846;

CommandLevel LevelOf(const std::string& action) {
  return action == "thrusts" ? CommandLevel::kRotorThrusts
         : action == "ctbm"  ? CommandLevel::kThrustMoment
         : action == "ctbr"  ? CommandLevel::kThrustRates
                             : CommandLevel::kThrustAttitude;  // ctatt, and velocity's output
}

// The velocity loop of a "velocity" action: aerobox's position controller with no position
// gain, so that the velocity asked for is its setpoint, limited to the action's range.
PositionControlParams VelocityLoop(const EnvParams& params) {
  PositionControlParams p;
  p.position_gain = Vec3::Zero();
  p.max_speed_horizontal = params.max_speed * std::sqrt(2.0);
  p.max_speed_vertical = params.max_speed;
  p.max_tilt = params.max_tilt;
  return p;
}

}  // namespace

EnvWorld::EnvWorld(const EnvParams& params, std::unique_ptr<VehiclePhysics> physics, const Map& map)
    : params_(params),
      vehicle_(params.Vehicle()),
      physics_(std::move(physics)),
      task_(FindEnvTask(params.task).make(params, vehicle_, map)),
      velocity_(params.action == "velocity"),
      level_(LevelOf(params.action)),
      velocity_loop_(VelocityLoop(params), vehicle_.mass),
      steps_per_control_(std::lround(1.0 / (params.control_rate * physics_->timestep()))) {
  params_.Validate();
  random_.Seed(StreamSeed(1, SeedStream::kEnvironment));
  loop_.vehicle = &vehicle_;
  loop_.control_rate = params.control_rate;
  loop_.inner = ControllerConfig().inner;
  loop_.aero.body_drag = loop_.aero.rotor_drag =
      params.drag || params.wind_speed > 0 || params.wind_turbulence > 0 || params.gust_speed > 0;
  loop_.sensors.imu.enabled = loop_.sensors.position.enabled = params.sensors;
}

void EnvWorld::Vary(std::uint64_t seed) {
  EnvRandom r;
  r.Seed(StreamSeed(seed, SeedStream::kEnvironment));
  const auto factor = [&r](double f) { return r.Uniform(1.0 - f, 1.0 + f); };
  VehicleScaling s;
  s.mass = factor(params_.vary_mass);
  s.inertia = Vec3::Constant(factor(params_.vary_inertia));
  for (int i = 0; i < 4; ++i) {
    s.thrust[i] = factor(params_.vary_thrust);
    s.yaw_moment[i] = factor(params_.vary_yaw_moment);
    s.motor_lag[i] = factor(params_.vary_motor_lag);
    s.rotor_limit[i] = factor(params_.vary_rotor_limit);
  }
  if (params_.Varies()) physics_->ScaleVehicle(s);
  const double heading = r.Uniform(-kPi, kPi);
  loop_.wind.mean =
      r.Uniform(0.0, params_.wind_speed) * Vec3(std::cos(heading), std::sin(heading), 0.0);
  const double intensity = r.Uniform(0.0, params_.wind_turbulence);
  loop_.wind.turbulence = intensity > 0 ? Turbulence::kDryden : Turbulence::kNone;
  loop_.wind.intensity = Vec3(1.0, 1.0, 0.5) * intensity;
  const double noise = factor(params_.vary_sensor_noise);
  const SensorParams nominal;
  loop_.sensors.imu.gyro_noise_density = nominal.imu.gyro_noise_density * noise;
  loop_.sensors.imu.accel_noise_density = nominal.imu.accel_noise_density * noise;
  loop_.sensors.position.noise = nominal.position.noise * noise;
  loop_.sensors.position.attitude_noise = nominal.position.attitude_noise * noise;
  Gust gust;
  gust.start = r.Uniform(0.0, params_.episode_time);
  gust.duration = r.Uniform(1.0, 3.0);
  gust.peak = r.Uniform(0.0, params_.gust_speed);
  const double towards = r.Uniform(-kPi, kPi);
  gust.direction = Vec3(std::cos(towards), std::sin(towards), 0.0);
  loop_.wind.gusts.clear();
  if (gust.peak > 0) loop_.wind.gusts.push_back(gust);
}

void EnvWorld::Reset(std::optional<std::uint64_t> seed, float* observation,
                     const EnvOptions& options) {
  task_->Check(options);  // before anything changes
  if (seed) random_.Seed(StreamSeed(*seed, SeedStream::kEnvironment));
  const State start = task_->Begin(random_, options);
  loop_.seed = random_.Next();
  physics_->ResetData();
  Vary(loop_.seed);  // the episode's vehicle (its scaling resets the data too) and wind
  physics_->SetVehicleState(start);
  physics_->SetRotorThrusts(Vec4::Constant(vehicle_.HoverThrustPerRotor()));
  world_.emplace(loop_, physics_.get());
  velocity_loop_.Reset();
  t_ = 0.0;
  state_ = physics_->VehicleState();
  seen_ = world_->Seen(state_);
  last_action_.fill(0.0);
  Observe(observation);
}

ControlCommand ActionCommand(const EnvParams& params, const QuadParams& vehicle, const double* a) {
  const double low = vehicle.MinRotorThrust(), high = vehicle.MaxRotorThrust();
  const auto rotor = [&](double x) { return low + 0.5 * (x + 1.0) * (high - low); };
  ControlCommand c;
  c.level = LevelOf(params.action);
  c.thrust = 4.0 * rotor(a[0]);
  if (c.level == CommandLevel::kRotorThrusts) {
    for (int i = 0; i < 4; ++i) c.rotor_thrusts[i] = rotor(a[i]);
  } else if (c.level == CommandLevel::kThrustMoment) {
    const double roll_pitch = high * vehicle.ArmLength();
    const double yaw = 2.0 * high * vehicle.yaw_moment_per_thrust;
    c.moment_B = Vec3(a[1] * roll_pitch, a[2] * roll_pitch, a[3] * yaw);
  } else if (c.level == CommandLevel::kThrustRates) {
    c.rate_B = Vec3(a[1], a[2], a[3]) * params.max_rate;
  } else {
    c.q_WB = Quat(Eigen::AngleAxisd(a[3] * kPi, Vec3::UnitZ())) *
             Quat(Eigen::AngleAxisd(a[2] * params.max_tilt, Vec3::UnitY())) *
             Quat(Eigen::AngleAxisd(a[1] * params.max_tilt, Vec3::UnitX()));
  }
  return c;
}

ControlCommand EnvWorld::CommandOf(const double* a) {
  if (!velocity_) return ActionCommand(params_, vehicle_, a);
  ControlCommand c;
  c.level = level_;
  PositionSetpoint setpoint;
  setpoint.p_W = seen_.p_W;
  setpoint.v_W = Vec3(a[0], a[1], a[2]) * params_.max_speed;
  setpoint.yaw = a[3] * kPi;
  AttitudeSetpoint out;
  out.thrust = vehicle_.mass * kGravity;
  velocity_loop_.Update(setpoint, seen_.p_W, seen_.v_W, seen_.q_WB, 1.0 / params_.control_rate,
                        &out);  // a state that is not finite keeps the level hover
  c.thrust = out.thrust;
  c.q_WB = out.q_WB;
  return c;
}

EnvStep EnvWorld::Step(const double* action, float* observation) {
  Begin(action);
  while (Stepping()) {
    physics_->Step(BeforePhysics());
    AfterPhysics();
  }
  return End(action, observation);
}

void EnvWorld::Begin(const double* action) {
  command_ = CommandOf(action);
  truth_ = world_->Truth();
  substep_ = 0;
  touched_ = false;
}

const Vec4& EnvWorld::BeforePhysics() {
  world_->Command(command_, world_->Seen(truth_));
  world_->BeforePhysics(truth_);
  return world_->inner().mixer.thrusts;
}

void EnvWorld::AfterPhysics() {
  truth_ = world_->AfterPhysics(truth_);
  touched_ = physics_->VehicleTouches();
  ++substep_;
}

EnvStep EnvWorld::End(const double* action, float* observation) {
  world_->EndControlPeriod();
  t_ += 1.0 / params_.control_rate;
  state_ = world_->Truth();
  seen_ = world_->Seen(state_);
  const bool finite = state_.AllFinite() && seen_.AllFinite();
  TaskScore score = task_->Score(t_, state_, action);
  EnvStep out;
  out.terminated = touched_ || !finite || score.ended || !physics_->TakeNewWarnings().empty();
  out.truncated = !out.terminated && t_ >= params_.episode_time - 1e-9;
  out.terms = std::move(score.terms);
  for (double& term : out.terms) {
    if (!finite) term = 0.0;
    out.reward += term;
  }
  for (int i = 0; i < 4; ++i) last_action_[i] = action[i];
  Observe(observation);
  return out;
}

void EnvWorld::Observe(float* o) const {
  const State& s = seen_;
  const Vec3 d = s.p_W - task_->Reference(t_);
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
  task_->Observe(t_, s, o + n);
}

}  // namespace aerobox
