#include "bench/robustness.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "common/error.h"
#include "common/number_format.h"
#include "control/controllers.h"
#include "mission/mission.h"
#include "mission/reference_curves.h"
#include "scenario/scenario.h"

namespace aerobox {
namespace {

constexpr double kPi = 3.14159265358979323846;

double Median(std::vector<double> values) {
  if (values.empty()) return std::nan("");
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

struct Run {
  int seed = 0;
  MissionStatus status = MissionStatus::kNoPath;
  std::string why;  // the flight's status (and the obstacle) when it failed
  double rms = 0, max = 0, clearance = 0, estimate = 0;
};

// One map, controller and wind over the seeds.
struct Cell {
  std::string map, controller;
  double wind = 0;  // [m/s]
  std::vector<Run> runs;
  int reached() const {
    return static_cast<int>(std::count_if(runs.begin(), runs.end(), [](const Run& r) {
      return r.status == MissionStatus::kReachedGoal;
    }));
  }
};

// "kind" or "kind+observer" into `config`.
void ApplyController(const std::string& name, ControllerConfig* config) {
  const size_t plus = name.find('+');
  config->kind = name.substr(0, plus);
  config->observer.enabled = plus != std::string::npos;
}

// The set-up of one flight: the scenario, its seed, the controller, a mean wind of `speed` from
// a direction that turns with the seed (so every map meets the wind from all sides),
// MIL-F-8785C turbulence for that wind at 20 ft (a calm day's 1 m/s when there is none), drag,
// an IMU and motion capture.
FlightSetup WindySetup(const std::string& scenario, int seed, const std::string& controller,
                       double speed) {
  SetupOverrides overrides;
  overrides.seed = static_cast<std::uint64_t>(seed);
  FlightSetup setup = LoadFlightSetup(scenario, overrides);
  ApplyController(controller, &setup.controller);
  const double angle = 2 * kPi * (seed - 1) / 20.0;
  setup.wind.mean = speed * Vec3(std::cos(angle), std::sin(angle), 0.0);
  setup.wind.turbulence = Turbulence::kDryden;
  setup.wind.intensity = DrydenIntensities(std::max(speed, 1.0), 6.1);
  setup.aero = AeroParams{true, true};
  FollowTheAir(false, false, &setup);  // drag fed forward, se3's integral in wind
  setup.sensors.imu.enabled = true;
  setup.sensors.position.enabled = true;
  return setup;
}

Run Fly(const FlightSetup& setup, int seed) {
  const MissionResult result = RunMission(setup, MissionParts());
  Run run;
  run.seed = seed;
  run.status = result.status;
  if (result.flown) {
    const FlightResult& f = result.flight;
    run.rms = f.rms_error;
    run.max = f.max_error;
    run.clearance = f.min_clearance;
    run.estimate = f.estimate_rms_error;
  }
  run.why = Outcome(result);
  return run;
}

void PrintRow(const Cell& cell, std::ostream& out) {
  std::vector<double> rms, estimate;
  double worst_rms = 0, worst_max = 0, least_clearance = INFINITY;
  std::string failures;
  for (const Run& r : cell.runs) {
    if (r.status != MissionStatus::kReachedGoal) {
      failures += (failures.empty() ? "" : ", ") + std::to_string(r.seed) + ": " + r.why;
    }
    if (r.status == MissionStatus::kNoPath || r.status == MissionStatus::kNoTrajectory) continue;
    rms.push_back(r.rms);
    estimate.push_back(r.estimate);
    worst_rms = std::max(worst_rms, r.rms);
    worst_max = std::max(worst_max, r.max);
    least_clearance = std::min(least_clearance, r.clearance);
  }
  const Vec3 sigma = DrydenIntensities(std::max(cell.wind, 1.0), 6.1);
  out << std::fixed << std::setprecision(2) << "| " << cell.map << " | " << cell.controller << " | "
      << cell.wind << " | " << sigma.x() << ", " << sigma.y() << ", " << sigma.z() << " | "
      << cell.reached() << "/" << cell.runs.size() << " | " << std::setprecision(3) << Median(rms)
      << " (" << worst_rms << ") | " << worst_max << " | " << least_clearance << " | "
      << std::setprecision(2) << 1e3 * Median(estimate) << " | "
      << (failures.empty() ? "none" : failures) << " |\n"
      << std::defaultfloat;
}

// The rest of a table's header, a column per wind [m/s].
void WindColumns(const std::vector<double>& winds, std::ostream& out) {
  for (const double wind : winds) out << " " << FormatNumber(wind) << " m/s |";
  out << "\n|---|";
  for (size_t i = 0; i < winds.size(); ++i) out << "---|";
  out << "\n";
}

// Per controller and wind: the flights that reached the goal, over every map.
void PrintTotals(const RobustnessParams& params, const std::vector<Cell>& cells,
                 std::ostream& out) {
  out << "| controller |";
  WindColumns(params.winds, out);
  for (const std::string& controller : params.controllers) {
    out << "| " << controller << " |";
    for (const double wind : params.winds) {
      int reached = 0, flights = 0;
      for (const Cell& c : cells) {
        if (c.controller != controller || c.wind != wind) continue;
        reached += c.reached();
        flights += static_cast<int>(c.runs.size());
      }
      out << " " << reached << "/" << flights << " |";
    }
    out << "\n";
  }
}

// Neural-Fly's wind-tunnel flights: the mean position error [cm] on its figure-8 at up to about
// 2 m/s, computed from its published logs, at these wind speeds [m/s].
constexpr double kNeuralFlyWinds[] = {0.0, 4.2, 8.5, 12.1};
struct PublishedErrors {
  const char* controller;
  double error_cm[4];
};
constexpr PublishedErrors kNeuralFly[] = {{"PID-type baseline", {10.3, 9.4, 13.9, 21.1}},
                                          {"INDI", {6.8, 5.8, 8.1, 9.5}},
                                          {"L1 adaptive", {4.6, 5.8, 11.3, 21.1}}};

// The mean position error [m] of one figure-8 in a constant wind of `speed` [m/s] along x, with
// drag, an IMU and motion capture; NaN when the flight does not end well.
double EightMeanError(const std::string& controller, double speed) {
  FlightSetup air;  // the controller's defaults that follow the air, as a scenario's do
  air.wind.mean = Vec3(speed, 0, 0);
  air.aero = AeroParams{true, true};
  ApplyController(controller, &air.controller);
  FollowTheAir(false, false, &air);
  const ControllerConfig& control = air.controller;
  const QuadParams vehicle;
  const std::unique_ptr<Controller> made = MakeController(control, vehicle);
  FlightLoop loop;
  loop.vehicle = &vehicle;
  loop.controller = made.get();
  loop.control_rate = control.rate;
  loop.inner = control.inner;
  loop.wind = air.wind;
  loop.aero = air.aero;
  loop.sensors.imu.enabled = true;
  loop.sensors.position.enabled = true;
  double sum = 0;
  long samples = 0;
  loop.telemetry = [&](const TelemetrySample& s) {
    sum += s.position_error;
    ++samples;
  };
  Simulation sim = RoomAt(Eight(0.0), Map(), vehicle);
  const FlightResult result =
      FlyTrajectory(FromFunction(EightDuration(), Eight), FlightParams(), loop, &sim);
  const bool ok = result.status == FlightStatus::kReachedGoal && samples > 0;
  return ok ? sum / samples : std::nan("");
}

}  // namespace

std::vector<std::string> RobustnessControllers(const std::string& list) {
  std::vector<std::string> controllers;
  std::istringstream names(list);
  for (std::string name; std::getline(names, name, ',');) controllers.push_back(name);
  ValidateRobustnessControllers(controllers);
  return controllers;
}

void ValidateRobustnessControllers(const std::vector<std::string>& controllers) {
  if (controllers.empty()) throw std::invalid_argument("no controller given");
  for (const std::string& name : controllers) {
    ControllerConfig config;
    ApplyController(name, &config);
    const bool suffix_ok =
        name.find('+') == std::string::npos || name.substr(name.find('+')) == "+observer";
    if (Controllers().Find(config.kind) == nullptr || !suffix_ok ||
        (config.kind == "indi" && config.observer.enabled)) {
      throw std::invalid_argument("controller \"" + name + "\": expected one of " +
                                  Controllers().NameList() +
                                  ", alone or with +observer (but indi, which measures the force "
                                  "itself)");
    }
  }
}

void RobustnessTable(const RobustnessParams& params, std::ostream& out, ProgressDisplay& progress) {
  ValidateRobustnessControllers(params.controllers);
  std::ofstream csv;
  if (!params.csv.empty()) {
    csv.open(params.csv);
    if (!csv) throw InputError({params.csv, 0}, "--robustness-csv", "cannot write");
    csv << "map,controller,wind_mps,seed,status,tracking_rms_m,tracking_max_m,min_clearance_m,"
           "estimate_rms_m\n";
  }
  // a row as each cell ends (an interrupted run keeps the rows done), then the totals
  out << "| map | controller | mean wind [m/s] | turbulence u, v, w [m/s] | reached | tracking "
         "RMS, median (worst) [m] | tracking max, worst [m] | min clearance, least [m] | "
         "estimate RMS, median [mm] | failures (seed: why) |\n"
         "|---|---|---|---|---|---|---|---|---|---|\n";
  std::vector<Cell> cells;
  for (const std::string& scenario : params.scenarios) {
    const std::string name = std::filesystem::path(scenario).parent_path().filename().string();
    for (const std::string& controller : params.controllers) {
      for (const double speed : params.winds) {
        Cell cell{name, controller, speed, {}};
        for (int seed = 1; seed <= params.seeds; ++seed) {
          progress.Show("robustness: " + name + ", " + controller + ", " + FormatNumber(speed) +
                        " m/s, seed " + std::to_string(seed));
          const Run run = Fly(WindySetup(scenario, seed, controller, speed), seed);
          if (csv) {
            csv << name << "," << controller << "," << speed << "," << seed << "," << run.why << ","
                << run.rms << "," << run.max << "," << run.clearance << "," << run.estimate << "\n";
          }
          cell.runs.push_back(run);
        }
        progress.Clear();
        PrintRow(cell, out);
        out << std::flush;
        cells.push_back(cell);
      }
    }
  }
  out << "\nReached the goal, over every map:\n\n";
  PrintTotals(params, cells, out);
  out << std::flush;
}

void WindEightTable(const RobustnessParams& params, std::ostream& out, ProgressDisplay& progress) {
  ValidateRobustnessControllers(params.controllers);
  out << "Figure-8 (4 x 2 m, at up to 2 m/s, one loop) in a constant wind along x, drag, IMU and "
         "motion capture: mean position error [cm] (-: the flight failed)\n\n| controller |";
  WindColumns(params.winds, out);
  for (const std::string& controller : params.controllers) {
    out << "| " << controller << " |";
    for (const double wind : params.winds) {
      progress.Show("robustness: figure-8, " + controller + ", " + FormatNumber(wind) + " m/s");
      const double error = EightMeanError(controller, wind);
      std::ostringstream cell;
      cell << std::fixed << std::setprecision(1) << 100 * error;
      out << " " << (std::isnan(error) ? std::string("-") : cell.str()) << " |";
    }
    out << "\n" << std::flush;
  }
  progress.Clear();
  out << "\nPublished by Neural-Fly (O'Connell et al., Science Robotics 2022; mean position error "
         "[cm] on a figure-8 at up to about 2 m/s, from its logs): real flights of its own "
         "vehicle in a wind tunnel, where ours are simulated Tello flights in a steady wind\n\n"
         "| controller |";
  WindColumns({std::begin(kNeuralFlyWinds), std::end(kNeuralFlyWinds)}, out);
  for (const PublishedErrors& row : kNeuralFly) {
    out << "| " << row.controller << " |";
    for (const double error : row.error_cm) out << " " << FormatNumber(error) << " |";
    out << "\n";
  }
}

}  // namespace aerobox
