#include "envs/swarm_world.h"

#include <cmath>
#include <stdexcept>

#include "envs/env_world.h"
#include "scene/scene_mjcf.h"

namespace aerobox {
namespace {

std::unique_ptr<Simulation> RoomWith(const QuadParams& vehicle, int agents, const Aabb& room,
                                     double physics_rate) {
  Map map;
  map.name = "swarm room";
  map.bounds = room;
  std::vector<SceneVehicle> vehicles;
  std::vector<std::string> names;
  for (int i = 0; i < agents; ++i) {
    names.push_back("agent_" + std::to_string(i));
    // apart on the floor until Reset places them
    const Vec3 p(room.min.x() + 0.5 + 0.5 * i, room.min.y() + 0.5, 1.0);
    vehicles.push_back({names.back(), vehicle, VehicleRestPosition(map, vehicle, p), SwarmRgba(i)});
  }
  SceneOptions options;
  options.timestep = 1.0 / physics_rate;
  return std::make_unique<Simulation>(
      Simulation::FromXml(BuildSceneMjcf(map, vehicles, options), "swarm room", names));
}

}  // namespace

SwarmWorld::SwarmWorld(const EnvParams& params, int agents, const Aabb& room)
    : params_(params), vehicle_(params.Vehicle()) {
  params_.Validate();
  if (params_.action == "velocity") {
    throw std::invalid_argument("action: \"velocity\" is not available with several agents");
  }
  if (agents < 1 || agents > 64) {
    throw std::invalid_argument("agents: expected 1 to 64, got " + std::to_string(agents));
  }
  if (!(room.Size().array() > 1.0).all()) {
    throw std::invalid_argument("the room must be larger than 1 m on every side");
  }
  sim_ = RoomWith(vehicle_, agents, room, params_.physics_rate);
  steps_per_control_ = std::lround(1.0 / (params_.control_rate * sim_->timestep()));
  loop_.vehicle = &vehicle_;
  loop_.control_rate = params_.control_rate;
  loop_.inner = ControllerConfig().inner;
  worlds_.resize(static_cast<size_t>(agents));
}

void SwarmWorld::Reset(const std::vector<Vec3>& starts) {
  if (static_cast<int>(starts.size()) != agents()) {
    throw std::invalid_argument("reset: one start per agent");
  }
  sim_->ResetData();
  for (int i = 0; i < agents(); ++i) {
    MujocoVehicle& v = sim_->vehicle(i);
    v.SetVehicleState(State{starts[i], Vec3::Zero(), Quat::Identity(), Vec3::Zero()});
    v.SetRotorThrusts(Vec4::Constant(vehicle_.HoverThrustPerRotor()));
  }
  for (int i = 0; i < agents(); ++i) {
    worlds_[i] = std::make_unique<VehicleWorld>(loop_, &sim_->vehicle(i));
    sim_->vehicle(i).TakeNewWarnings();
  }
  t0_ = sim_->time();
}

std::vector<std::string> SwarmWorld::Step(const std::vector<const double*>& actions) {
  if (static_cast<int>(actions.size()) != agents()) {
    throw std::invalid_argument("step: one action (or none) per agent");
  }
  std::vector<ControlCommand> commands(actions.size());
  for (size_t i = 0; i < actions.size(); ++i) {
    if (actions[i] != nullptr) commands[i] = ActionCommand(params_, vehicle_, actions[i]);
  }
  std::vector<std::string> touched(actions.size());
  for (long k = 0; k < steps_per_control_; ++k) {
    for (int i = 0; i < agents(); ++i) {
      VehicleWorld& w = *worlds_[i];
      const State truth = w.Truth();
      Vec4 rotors = Vec4::Zero();
      if (actions[i] != nullptr && w.Command(commands[i], truth)) rotors = w.inner().mixer.thrusts;
      sim_->vehicle(i).SetCommands(rotors);
    }
    sim_->StepWorld();
    // MuJoCo distrusts the state it stepped to (it reset it): every agent is out
    if (const std::string warning = sim_->TakeNewWarnings(); !warning.empty()) {
      for (std::string& t : touched) t = "MuJoCo's warning: " + warning;
      return touched;
    }
    for (int i = 0; i < agents(); ++i) {
      if (!touched[i].empty()) continue;
      for (const VehicleContact& c : sim_->vehicle(i).VehicleContacts()) touched[i] = c.other_geom;
    }
  }
  return touched;
}

}  // namespace aerobox
