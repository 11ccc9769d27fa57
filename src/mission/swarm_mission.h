// A run of several vehicles in one world (a scenario's [[vehicles]]): each vehicle plans its own
// path and trajectory against the map, the plans are kept apart in space and time (SwarmParams'
// prioritised planning), and all fly at once in one MuJoCo world (FlySwarm).
#pragma once

#include <string>
#include <vector>

#include "mission/mission.h"
#include "mission/setup.h"
#include "mission/swarm.h"

namespace aerobox {

// When and how one vehicle flies its plan among the others.
struct SwarmSchedule {
  bool flies = false;     // false: it holds its start (no path, no trajectory, or no clear plan)
  double delay = 0.0;     // [s] it waits at its start before its trajectory starts
  std::string detour;     // "" or how its path was bent to keep clear ("0.35 m up")
  std::string note;       // why it does not fly, in words ("" when it flies)
  double duration = 0.0;  // [s] of its trajectory alone (without the wait)
};

struct SwarmMissionResult {
  std::vector<PlanOutcome> plans;  // each vehicle's own, against the map alone
  std::vector<SwarmSchedule> schedule;
  SwarmFlightResult flight;
  double flight_wall_time = 0.0;  // [s]
  // the last arrival on the shared clock as scheduled (waits and trajectories), as flown (the
  // last flight that reached its goal, within its tolerance), and the longest trajectory flown
  // alone [s]
  double makespan = 0.0;
  double flown_makespan = 0.0;
  double alone_makespan = 0.0;
  bool AllReached() const;
};

// One list of observers per vehicle (fewer lists: the rest unobserved), each told of its own
// vehicle's plan, flight start, samples and end as MissionObserver says; and the world's (its
// pictures), told of the scene, the first vehicle's plan and flight start, then the first
// vehicle's state every control period of its rate through the whole flight (it goes on while
// that vehicle holds its goal), and at the end the result of the first vehicle that failed (or
// the first's), timed at the last flight's end.
struct SwarmParts {
  std::vector<std::vector<MissionObserver*>> observers;
  std::vector<MissionObserver*> world;
};

// Plans each vehicle (PlanFlight of FlightSetup::Member), schedules them apart (prioritised: in
// the order given, each waits at its start or bends its path around the middle until it keeps
// separation from those before it; a vehicle that cannot holds its start, and so does any that
// would pass through a vehicle that holds), loads one scene with every vehicle and flies them
// all. Throws as RunMission does.
SwarmMissionResult RunSwarm(const FlightSetup& setup, const SwarmParts& parts);

}  // namespace aerobox
