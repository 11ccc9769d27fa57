#include "bench/replanning_benchmark.h"

#include <algorithm>
#include <filesystem>
#include <iomanip>

#include "mission/mission.h"
#include "scenario/scenario.h"

namespace aerobox {

void ReplanningTable(const std::vector<std::string>& scenarios, int seeds, double fraction,
                     std::ostream& out, ProgressDisplay& progress) {
  out << "| map | unknown boxes | reached | contacts | replans | latency median [ms] | latency "
         "worst [ms] | slowest (seed: outcome) | failures (seed: why) "
         "|\n|---|---|---|---|---|---|---|---|---|\n";
  std::vector<double> all;
  int total = 0, reached_all = 0, capped = 0;
  for (const std::string& scenario : scenarios) {
    const std::string name = std::filesystem::path(scenario).parent_path().filename().string();
    int reached = 0, contacts = 0, replans = 0, unknown = 0;
    std::vector<double> latency;
    std::string failures, slowest;
    double slowest_latency = -1.0;  // [s]
    for (int seed = 1; seed <= seeds; ++seed) {
      progress.Show("replanning: " + name + ", seed " + std::to_string(seed));
      SetupOverrides overrides;
      overrides.seed = static_cast<std::uint64_t>(seed);
      FlightSetup setup = LoadFlightSetup(scenario, overrides);
      setup.unknown = UnknownBoxes(setup.map, {}, fraction, setup.seed);
      const MissionResult result = RunMission(setup, MissionParts());
      unknown = result.unknown_boxes;
      if (result.status == MissionStatus::kReachedGoal) {
        ++reached;
      } else {
        failures += (failures.empty() ? "" : ", ") + std::to_string(seed) + ": " + Outcome(result);
      }
      if (result.flown && result.flight.status == FlightStatus::kCollision) ++contacts;
      for (const ReplanEvent& e : result.replans) {
        ++replans;
        capped += e.time_capped ? 1 : 0;
        latency.push_back(e.latency);
        if (e.latency > slowest_latency) {
          slowest_latency = e.latency;
          slowest = std::to_string(seed) + ": " + e.outcome;
        }
        all.push_back(e.latency);
      }
    }
    total += seeds;
    reached_all += reached;
    std::sort(latency.begin(), latency.end());
    const double median = latency.empty() ? 0.0 : latency[latency.size() / 2];
    const double worst = latency.empty() ? 0.0 : latency.back();
    out << std::fixed << std::setprecision(1) << "| " << name << " | " << unknown << " | "
        << reached << "/" << seeds << " | " << contacts << " | " << replans << " | " << 1e3 * median
        << " | " << 1e3 * worst << " | " << (slowest.empty() ? "none" : slowest) << " | "
        << (failures.empty() ? "none" : failures) << " |\n"
        << std::defaultfloat << std::flush;
  }
  std::sort(all.begin(), all.end());
  out << "\nAll maps: " << reached_all << "/" << total << " reached every goal; " << all.size()
      << " replans, latency median " << std::fixed << std::setprecision(1)
      << (all.empty() ? 0.0 : 1e3 * all[all.size() / 2]) << " ms, worst "
      << (all.empty() ? 0.0 : 1e3 * all.back()) << " ms; " << capped
      << " cut by the wall-time cap (the rest depend on the seed alone)\n"
      << std::defaultfloat;
  progress.Clear();
}

}  // namespace aerobox
