#include "bench/robustness.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "common/error.h"
#include "common/number_format.h"
#include "mission/mission.h"
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

// The set-up of one flight: the scenario, its seed, a mean wind of `speed` from a direction
// that turns with the seed (so every map meets the wind from all sides), MIL-F-8785C
// turbulence for that wind at 20 ft (a calm day's 1 m/s when there is none), drag, an IMU and
// motion capture.
FlightSetup WindySetup(const std::string& scenario, int seed, double speed) {
  SetupOverrides overrides;
  overrides.seed = static_cast<std::uint64_t>(seed);
  FlightSetup setup = LoadFlightSetup(scenario, overrides);
  const double angle = 2 * kPi * (seed - 1) / 20.0;
  setup.wind.mean = speed * Vec3(std::cos(angle), std::sin(angle), 0.0);
  setup.wind.turbulence = Turbulence::kDryden;
  setup.wind.intensity = DrydenIntensities(std::max(speed, 1.0), 6.1);
  setup.aero = AeroParams{true, true};
  setup.controller.drag_feedforward = true;
  setup.sensors.imu.enabled = true;
  setup.sensors.position.enabled = true;
  return setup;
}

}  // namespace

void RobustnessTable(const RobustnessParams& params, std::ostream& out, ProgressDisplay& progress) {
  std::ofstream csv;
  if (!params.csv.empty()) {
    csv.open(params.csv);
    if (!csv) throw InputError({params.csv, 0}, "--robustness-csv", "cannot write");
    csv << "map,wind_mps,seed,status,tracking_rms_m,tracking_max_m,min_clearance_m,"
           "estimate_rms_m\n";
  }
  out << "| map | mean wind [m/s] | turbulence u, v, w [m/s] | reached | tracking RMS, median "
         "(worst) [m] | tracking max, worst [m] | min clearance, least [m] | estimate RMS, "
         "median [mm] | failures (seed: why) |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const std::string& scenario : params.scenarios) {
    const std::string name = std::filesystem::path(scenario).parent_path().filename().string();
    for (const double speed : params.winds) {
      std::vector<Run> runs;
      for (int seed = 1; seed <= params.seeds; ++seed) {
        progress.Show("robustness: " + name + ", " + FormatNumber(speed) + " m/s, seed " +
                      std::to_string(seed));
        const FlightSetup setup = WindySetup(scenario, seed, speed);
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
        if (csv) {
          csv << name << "," << speed << "," << seed << "," << run.why << "," << run.rms << ","
              << run.max << "," << run.clearance << "," << run.estimate << "\n";
        }
        runs.push_back(run);
      }
      std::vector<double> rms, estimate;
      double worst_rms = 0, worst_max = 0, least_clearance = INFINITY;
      int reached = 0;
      std::string failures;
      for (const Run& r : runs) {
        if (r.status == MissionStatus::kReachedGoal) ++reached;
        if (r.status != MissionStatus::kReachedGoal) {
          failures += (failures.empty() ? "" : ", ") + std::to_string(r.seed) + ": " + r.why;
        }
        if (r.status == MissionStatus::kNoPath || r.status == MissionStatus::kNoTrajectory) {
          continue;
        }
        rms.push_back(r.rms);
        estimate.push_back(r.estimate);
        worst_rms = std::max(worst_rms, r.rms);
        worst_max = std::max(worst_max, r.max);
        least_clearance = std::min(least_clearance, r.clearance);
      }
      const Vec3 sigma = DrydenIntensities(std::max(speed, 1.0), 6.1);
      out << std::fixed << std::setprecision(2) << "| " << name << " | " << speed << " | "
          << sigma.x() << ", " << sigma.y() << ", " << sigma.z() << " | " << reached << "/"
          << runs.size() << " | " << std::setprecision(3) << Median(rms) << " (" << worst_rms
          << ") | " << worst_max << " | " << least_clearance << " | " << std::setprecision(2)
          << 1e3 * Median(estimate) << " | " << (failures.empty() ? "none" : failures) << " |\n"
          << std::defaultfloat << std::flush;
    }
  }
  progress.Clear();
}

}  // namespace aerobox
