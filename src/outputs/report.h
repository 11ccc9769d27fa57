// report.html: one page that shows a whole run in a browser, from file:// with no network and
// no server. The map, the plan and the flight in 3-D (three.js), the numbers over time
// (Chart.js), a time slider, and the summary; the data and Debian's packaged scripts are copied
// into the page.
#pragma once

#include <string>
#include <vector>

#include "mission/mission.h"
#include "mission/telemetry_table.h"
#include "outputs/html_page.h"

namespace aerobox {

// Collects what the page shows as the run goes (telemetry at most every 10 ms of flight), then
// writes the page with Write.
class ReportOutputs : public MissionObserver {
 public:
  ReportOutputs(std::string folder, const FlightSetup& setup);
  void OnPlan(const PlanOutcome& plan) override;
  void OnFlightStart(const Simulation&, const Controller& controller) override;
  void OnSample(const TelemetrySample& sample) override;
  void OnFlightEnd(const Simulation& sim, const FlightResult& result) override;
  void OnDiscovery(const std::vector<double>& revealed_at,
                   const std::vector<ReplanEvent>& replans) override;
  // the occupied cells the planner avoids, once a second of flight
  void OnDepthFrame(double t, const DepthImage& image, const OccupancyGrid& map) override;

  // Writes <folder>/report.html with the run's summary.json text and the command that repeats
  // the run. Throws InputError naming a script that is missing (install libjs-three and
  // libjs-chart.js) or the page when it cannot be written.
  std::string Write(const std::string& summary_json, const std::string& command,
                    const ReportScripts& scripts = ReportScripts()) const;

  // The page of several vehicles in one world, each vehicle's run collected by its own
  // ReportOutputs (`vehicles`, named by `names`, drawn in `colours`, "r g b a"): the first's data
  // in the places a lone vehicle's go, every vehicle's in the page's "vehicles" list, which the
  // page draws in their colours and offers to the charts. Throws as Write does.
  static std::string WriteSwarm(const std::string& folder, const FlightSetup& setup,
                                const std::vector<const ReportOutputs*>& vehicles,
                                const std::vector<std::string>& names,
                                const std::vector<std::string>& colours,
                                const std::string& summary_json, const std::string& command,
                                const ReportScripts& scripts = ReportScripts());

 private:
  // This run's part of the page's data, as JSON text: "plan", "telemetry", "failure".
  std::string VehicleJson() const;

  std::string folder_;
  const FlightSetup& setup_;
  std::string plan_json_ = "{}";
  TelemetrySchema schema_;                    // the flying controller's
  std::vector<std::string> column_names_;     // the columns the page shows
  std::vector<int> column_index_;             // ... in schema_
  std::vector<std::vector<double>> columns_;  // ... their values every 10 ms
  double next_sample_ = 0.0;                  // [s]
  std::vector<double> revealed_at_;
  std::vector<ReplanEvent> replans_;
  // the occupancy map's occupied boxes at times [s] a second apart: (t, the boxes)
  std::vector<std::pair<double, std::vector<Aabb>>> occupied_;
  bool flown_ = false;
  FlightResult result_;
  Vec3 end_position_ = Vec3::Zero();
};

}  // namespace aerobox
