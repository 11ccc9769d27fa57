// Several vehicles in one MuJoCo world, for multi-agent learning (aerobox.marl's PettingZoo
// environment): every agent's action (EnvParams' levels and scaling, as one world's) is held
// over a control period while each vehicle's inner loops run at the physics rate and the world
// steps once for all. The task (starts, goals, observations, rewards) is the caller's.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "envs/env_params.h"
#include "mission/flight_parts.h"
#include "sim/simulation.h"

namespace aerobox {

class SwarmWorld {
 public:
  // `agents` vehicles of `params`' kind (named "agent_0", ...) in an empty room of `room` [m],
  // the floor at its lower z. Throws std::invalid_argument for bad parameters (a "velocity"
  // action, which needs each agent's own velocity loop, is refused).
  SwarmWorld(const EnvParams& params, int agents, const Aabb& room);

  int agents() const { return static_cast<int>(worlds_.size()); }
  double time() const { return sim_->time() - t0_; }  // [s] since the last Reset
  const QuadParams& vehicle() const { return vehicle_; }

  // Every vehicle at rest at its start [m], level, its rotors at hover thrust.
  void Reset(const std::vector<Vec3>& starts);
  // One control period: agent i flies `actions[i]` (ActionSize values in [-1, 1]; the caller
  // checks), or, when it is nullptr, has its rotors off (an agent that is out of the game).
  // Returns, per agent, what it touched during the period: "" nothing, a geom's name ("floor"),
  // another agent's name, or, for every agent, MuJoCo's warning (the state is not trusted).
  std::vector<std::string> Step(const std::vector<const double*>& actions);
  State state(int i) const { return sim_->vehicle(i).VehicleState(); }

 private:
  EnvParams params_;
  QuadParams vehicle_;
  std::unique_ptr<Simulation> sim_;
  FlightLoop loop_;
  std::vector<std::unique_ptr<VehicleWorld>> worlds_;
  long steps_per_control_;
  double t0_ = 0.0;
};

}  // namespace aerobox
