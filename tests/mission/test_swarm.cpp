// Several vehicles in one world: one vehicle flies as it flies alone, to the bit; two vehicles
// on crossing lines collide and both are told whom they hit; the downwash pushes a vehicle below
// another by the model's force; reservations keep planned trajectories apart.
#include <doctest/doctest.h>

#include <cmath>
#include <iostream>
#include <memory>

#include "flight_test_util.h"
#include "mission/swarm.h"
#include "mission/swarm_mission.h"
#include "scenario/scenario.h"
#include "scene/scene_mjcf.h"
#include "test_support.h"

namespace aerobox {
namespace {

using testing::FromFunction;

Map Room() {
  Map map;
  map.name = "room";
  map.bounds = {Vec3(-10, -10, 0), Vec3(10, 10, 6)};
  return map;
}

// A world of vehicles named by `names` at `starts`, hovering.
Simulation WorldOf(const std::vector<std::string>& names, const std::vector<Vec3>& starts,
                   const QuadParams& vehicle = QuadParams()) {
  std::vector<SceneVehicle> scene;
  for (size_t i = 0; i < names.size(); ++i) {
    scene.push_back({names[i], vehicle, starts[i], SwarmRgba(static_cast<int>(i))});
  }
  Simulation sim =
      Simulation::FromXml(BuildSceneMjcf(Room(), scene, SceneOptions()), "swarm room", names);
  for (int i = 0; i < sim.vehicle_count(); ++i) {
    sim.vehicle(i).SetRotorThrusts(Vec4::Constant(vehicle.HoverThrustPerRotor()));
  }
  return sim;
}

Reference Line(const Vec3& from, const Vec3& to, double duration) {
  return FromFunction(duration, [=](double t) {
    const double s = std::clamp(t / duration, 0.0, 1.0);
    const double smooth = s * s * s * (10 - 15 * s + 6 * s * s);
    return Vec3(from + smooth * (to - from));
  });
}

// Vehicles flying `references` from where each starts, every one with its own cascade.
struct Fleet {
  QuadParams vehicle;
  std::vector<std::unique_ptr<Controller>> controllers;
  std::vector<SwarmVehicle> vehicles;
  std::vector<std::vector<TelemetrySample>> samples;

  Fleet(const std::vector<std::string>& names, const std::vector<Reference>& references)
      : samples(names.size()) {
    for (size_t i = 0; i < names.size(); ++i) {
      controllers.push_back(MakeController(ControllerConfig(), vehicle));
      SwarmVehicle v;
      v.name = names[i];
      v.reference = references[i];
      v.loop.vehicle = &vehicle;
      v.loop.controller = controllers.back().get();
      v.loop.control_rate = ControllerConfig().rate;
      v.loop.inner = ControllerConfig().inner;
      v.loop.telemetry = [this, i](const TelemetrySample& s) { samples[i].push_back(s); };
      vehicles.push_back(std::move(v));
    }
  }
};

// A set-up of Crazyflies in the swap scene's room: `vehicles` is [[vehicles]] tables' text.
FlightSetup RoomSetup(const std::string& vehicles) {
  const std::string file = (testing::SourceDir() / "scenes" / "swarm_swap" / "x.toml").string();
  return LoadFlightSetupFromText("map = \"map.json\"\n[vehicle]\nkind = \"crazyflie\"\n" + vehicles,
                                 file, {});
}

std::string Vehicle(const char* name, const char* start, const char* goal) {
  return std::string("[[vehicles]]\nname = \"") + name + "\"\nstart = " + start +
         "\ngoal = " + goal + "\n";
}

FlightParams Params() {
  FlightParams params;
  params.settle_time = 2.0;
  return params;
}

}  // namespace

TEST_CASE("one vehicle of a swarm flies as the vehicle alone bit for bit") {
  const Reference line = Line(Vec3(0, 0, 1), Vec3(2, 1, 1.5), 3.0);
  // alone, in today's scene
  std::vector<TelemetrySample> alone;
  Simulation sim = testing::RoomAt(Vec3(0, 0, 1));
  const FlightResult single = FlyTrajectory(
      line, Params(), QuadParams(), ControllerConfig(), {},
      [&alone](const TelemetrySample& s) { alone.push_back(s); }, &sim);
  // the same vehicle as the one member of a swarm, its elements named after it
  Fleet fleet({"solo"}, {line});
  Simulation world = WorldOf({"solo"}, {Vec3(0, 0, 1)});
  const SwarmFlightResult swarm = FlySwarm(fleet.vehicles, Params(), SwarmParams(), &world);
  REQUIRE(swarm.flights.size() == 1);
  CHECK(swarm.flights[0].status == single.status);
  CHECK(swarm.flights[0].steps == single.steps);
  CHECK(swarm.flights[0].rms_error == single.rms_error);
  REQUIRE(fleet.samples[0].size() == alone.size());
  for (size_t k = 0; k < alone.size(); ++k) {
    CHECK(fleet.samples[0][k].state.p_W == alone[k].state.p_W);
    CHECK(fleet.samples[0][k].inner.mixer.thrusts == alone[k].inner.mixer.thrusts);
  }
}

TEST_CASE("two vehicles on crossing lines collide and each is told the other's name") {
  Fleet fleet({"north", "east"},
              {Line(Vec3(0, -1, 1), Vec3(0, 1, 1), 2.0), Line(Vec3(-1, 0, 1), Vec3(1, 0, 1), 2.0)});
  Simulation world = WorldOf({"north", "east"}, {Vec3(0, -1, 1), Vec3(-1, 0, 1)});
  const SwarmFlightResult result = FlySwarm(fleet.vehicles, Params(), SwarmParams(), &world);
  REQUIRE(result.flights.size() == 2);
  CHECK(result.flights[0].status == FlightStatus::kCollision);
  CHECK(result.flights[0].obstacle == "east");
  CHECK(result.flights[1].status == FlightStatus::kCollision);
  CHECK(result.flights[1].obstacle == "north");
  CHECK(result.flights[0].time == doctest::Approx(result.flights[1].time));
  CHECK(result.min_separation < VehicleRadius(QuadParams()) * 2);
  CHECK(result.closest_pair == "north and east");
}

TEST_CASE("two vehicles apart both arrive and the first to arrive holds its goal") {
  // the second crosses 1 m higher; the first's line is shorter, so it arrives first and hovers
  Fleet fleet({"low", "high"}, {Line(Vec3(0, -1, 1), Vec3(0, 0.5, 1), 1.5),
                                Line(Vec3(-1, 0, 2), Vec3(1, 0, 2), 3.0)});
  Simulation world = WorldOf({"low", "high"}, {Vec3(0, -1, 1), Vec3(-1, 0, 2)});
  const SwarmFlightResult result = FlySwarm(fleet.vehicles, Params(), SwarmParams(), &world);
  CHECK(result.AllReached());
  CHECK(result.flights[0].time < result.flights[1].time);
  // the first still hovers at its goal when the second arrives
  CHECK((world.vehicle(0).VehicleState().p_W - Vec3(0, 0.5, 1)).norm() < 0.02);
  CHECK(result.min_separation > 0.9);
  CHECK(result.vehicle_min_separation.size() == 2);
}

TEST_CASE("the downwash pushes a vehicle below another down by the model's force") {
  SwarmParams params;
  const QuadParams vehicle;
  // the formula, by hand: 0.5 m below, 5 cm across
  const double dz = 0.5, across = 0.05;
  const double a = params.downwash_c1 * std::pow(vehicle.propeller_radius / (4 * dz), 2);
  const double b = params.downwash_c2 * dz + params.downwash_c3;
  const double expected = -a * std::exp(-0.5 * std::pow(across / b, 2));
  const Vec3 force =
      DownwashForce(Vec3(across, 0, 1.5), Vec3(0, 0, 1.0), vehicle.propeller_radius, params);
  CHECK(force.z() == doctest::Approx(expected).epsilon(1e-12));
  CHECK(force.head<2>().norm() == 0.0);
  CHECK(DownwashForce(Vec3(0, 0, 1.0), Vec3(0, 0, 1.5), 0.02, params).norm() == 0.0);   // below
  CHECK(DownwashForce(Vec3(10, 0, 2.0), Vec3(0, 0, 1.0), 0.02, params).norm() == 0.0);  // far

  // in the world: one step at hover thrust, the lower vehicle's acceleration is the force / mass
  const auto first_step = [&](bool downwash) {
    Simulation world =
        WorldOf({"below", "above"}, {Vec3(0, 0, 1.0), Vec3(across, 0, 1.5)}, vehicle);
    params.downwash = downwash;
    Fleet fleet({"below", "above"}, {Line(Vec3(0, 0, 1), Vec3(0, 0, 1), 0.5),
                                     Line(Vec3(across, 0, 1.5), Vec3(across, 0, 1.5), 0.5)});
    FlightParams flight = Params();
    flight.settle_time = 0.0;
    // at 1 kHz the rule ends both flights before their second physics step
    for (SwarmVehicle& v : fleet.vehicles) {
      v.loop.control_rate = 1000.0;
      v.loop.terminate = [](double t, const State&) { return t > 0.0005; };
    }
    FlySwarm(fleet.vehicles, flight, params, &world);
    return world.vehicle(0).LinearAcceleration_W().z();
  };
  const double pushed = first_step(true) - first_step(false);
  std::cout << "downwash 0.5 m below: model " << expected << " N, measured "
            << pushed * vehicle.mass << " N\n";
  CHECK(pushed * vehicle.mass == doctest::Approx(expected).epsilon(1e-6));
}

TEST_CASE("a reservation delays a crossing start until the first vehicle has passed") {
  SwarmParams params;
  const double r = VehicleRadius(QuadParams());
  const Reservation first{Line(Vec3(0, -1, 1), Vec3(0, 1, 1), 2.0), r};
  const Reservation second{Line(Vec3(-1, 0, 1), Vec3(1, 0, 1), 2.0), r};
  CHECK(Check(first, second, params.separation).margin < 0);
  const std::optional<double> delay = ConflictFreeDelay(second, {first}, params);
  REQUIRE(delay.has_value());
  CHECK(*delay > 0.0);
  CHECK(Check(first, Reservation{Delayed(second.reference, *delay), r}, params.separation).margin >=
        0.0);
  // a vehicle parked on the other's goal can never be cleared by waiting
  const Reservation parked{Line(Vec3(0, 1, 1), Vec3(0, 1, 1), 0.1), r};
  CHECK_FALSE(ConflictFreeDelay(parked, {first}, params).has_value());
}

TEST_CASE("planned apart, two crossing vehicles pass with the separation margin") {
  const FlightSetup setup =
      RoomSetup(Vehicle("a", "[1, 0, 1]", "[-1, 0, 1]") + Vehicle("b", "[0, 1, 1]", "[0, -1, 1]"));
  const SwarmMissionResult result = RunSwarm(setup, SwarmParts());
  REQUIRE(result.flight.flights.size() == 2);
  CHECK(result.AllReached());
  CHECK(result.schedule[1].delay + static_cast<double>(!result.schedule[1].detour.empty()) > 0);
  // the plans keep 2 r + separation; the flights within their tracking errors of the plans
  const double r = VehicleRadius(setup.vehicles[0].vehicle);
  const double tracking = result.flight.flights[0].max_error + result.flight.flights[1].max_error;
  MESSAGE("crossing: " << result.flight.min_separation << " m apart at the closest, "
                       << 2 * r + setup.swarm.separation << " m planned, tracking within "
                       << tracking << " m");
  CHECK(result.flight.min_separation > 2 * r + setup.swarm.separation - tracking);
  // without planning they meet
  FlightSetup alone = setup;
  alone.swarm.planning = "none";
  const SwarmMissionResult met = RunSwarm(alone, SwarmParts());
  CHECK(met.flight.flights[0].status == FlightStatus::kCollision);
  CHECK(met.flight.flights[0].obstacle == "b");
}

TEST_CASE("a vehicle with no plan clear of the others holds its start and is reported") {
  // b's goal is within a vehicle of a's: no wait or bend clears it
  const FlightSetup setup = RoomSetup(Vehicle("a", "[1, 0, 1]", "[-1, 0, 1]") +
                                      Vehicle("b", "[0, 1, 1]", "[-0.9, 0, 1]"));
  const SwarmMissionResult result = RunSwarm(setup, SwarmParts());
  CHECK(result.schedule[0].flies);
  CHECK_FALSE(result.schedule[1].flies);
  CHECK(result.schedule[1].note.find("no plan keeps clear") == 0);
  CHECK(result.flight.flights[0].status == FlightStatus::kReachedGoal);
  CHECK_FALSE(result.AllReached());
  CHECK(result.flight.min_separation > 0.5);  // b never left its start
}

TEST_CASE("with walls unknown until seen each vehicle replans on its own") {
  const std::string file = (testing::SourceDir() / "scenes" / "maze" / "x.toml").string();
  const FlightSetup setup = LoadFlightSetupFromText(
      "map = \"map.json\"\nunknown_fraction = 0.3\nseed = 4\n"
      "[sensing]\nkind = \"omni\"\nrange = 3.0\nrate = 25.0\n" +
          Vehicle("a", "[1.0, 5.0, 1.5]", "[9.0, 7.0, 1.5]") +
          Vehicle("b", "[9.0, 1.0, 1.5]", "[1.5, 3.0, 1.5]"),
      file, {});
  REQUIRE(setup.HasUnknown());
  const SwarmMissionResult result = RunSwarm(setup, SwarmParts());
  CHECK(result.AllReached());
  // planned without the unknown walls, so at least one vehicle met one and replanned
  CHECK(result.flight.flights[0].replans + result.flight.flights[1].replans > 0);
  for (const FlightResult& f : result.flight.flights) CHECK(f.min_clearance > 0);
}

TEST_CASE("vehicles that start on the floor keep the planned timing and pass apart") {
  // b's path crosses a's; a climbs from the floor first: on the shared clock its trajectory
  // starts after the take-off time, as it was reserved (a take-off that held a's clock would
  // put it where b was told it would not be)
  const FlightSetup setup = RoomSetup(Vehicle("a", "[0, -1.5, 0]", "[0, 1.5, 1]") +
                                      Vehicle("b", "[-1.5, 0, 1]", "[1.5, 0, 1]"));
  const SwarmMissionResult result = RunSwarm(setup, SwarmParts());
  CHECK(result.AllReached());
  CHECK(result.schedule[0].delay >= setup.swarm.takeoff_time);
  const double r = VehicleRadius(setup.vehicles[0].vehicle);
  CHECK(result.flight.min_separation > 2 * r);
}

TEST_CASE("a vehicle that holds its start keeps hovering there, its mission not missed") {
  // b's goal is on a's: b holds its start, with a mission that must not count as missed
  const FlightSetup setup = RoomSetup(
      Vehicle("a", "[1, 0, 1]", "[-1, 0, 1]") +
      "[[vehicles]]\nname = \"b\"\nstart = [0, 1, 1]\ngoals = [[0, 0.5, 1], [-0.95, 0, 1]]\n");
  const SwarmMissionResult result = RunSwarm(setup, SwarmParts());
  REQUIRE_FALSE(result.schedule[1].flies);
  CHECK(result.flight.flights[1].status == FlightStatus::kReachedGoal);  // at its start, held
  CHECK((result.flight.flights[1].end_position - Vec3(0, 1, 1)).norm() < 0.05);
}

TEST_CASE("a vehicle that has arrived and holds its goal is hit: both are collisions") {
  // without planning, b flies through where a arrived and hovers
  Fleet fleet({"a", "b"}, {Line(Vec3(1, 0, 1), Vec3(0, 0, 1), 1.0),
                           Line(Vec3(0, -1.5, 1), Vec3(0, 1.5, 1), 3.0)});
  Simulation world = WorldOf({"a", "b"}, {Vec3(1, 0, 1), Vec3(0, -1.5, 1)});
  const SwarmFlightResult result = FlySwarm(fleet.vehicles, Params(), SwarmParams(), &world);
  CHECK(result.flights[0].status == FlightStatus::kCollision);
  CHECK(result.flights[0].obstacle == "b");
  CHECK(result.flights[1].status == FlightStatus::kCollision);
  CHECK(result.flights[1].obstacle == "a");
  CHECK(result.vehicle_min_clearance[0] < 0.01);
}

}  // namespace aerobox
