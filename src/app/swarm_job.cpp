#include "app/swarm_job.h"

#include <filesystem>
#include <iomanip>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>

#include "app/exit_codes.h"
#include "common/number_format.h"
#include "mission/swarm_mission.h"
#include "mission/telemetry_table.h"
#include "outputs/report.h"
#include "outputs/summary.h"
#include "scene/scene_mjcf.h"
#include "telemetry/json_object.h"

namespace aerobox {
namespace fs = std::filesystem;
namespace {

std::vector<double> Point(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

// Each vehicle's files in its own folder; the world's pictures with the first vehicle's plan.
struct SwarmOutputs {
  SwarmOutputs(const std::string& folder, const FlightSetup& setup, const FlyOptions& options,
               std::ostream& err)
      : first(setup.Member(0)) {
    for (size_t i = 0; i < setup.vehicles.size(); ++i) {
      const std::string own = (fs::path(folder) / setup.vehicles[i].name).string();
      fs::create_directories(own);
      members.push_back(std::make_unique<FlightSetup>(setup.Member(i)));
      const FlightSetup& member = *members.back();
      const int every = TelemetryEvery(options, member.controller.rate);
      csv.push_back(
          std::make_unique<CsvOutputs>(own, every, TelemetryExtrasFor(member), options.telemetry));
      parts.observers.push_back({csv.back().get()});
      if (options.report) {
        reports.push_back(std::make_unique<ReportOutputs>(folder, member));
        parts.observers.back().push_back(reports.back().get());
      }
    }
    if (options.video || options.overview || options.frames_every > 0) {
      pictures.emplace(folder, first, RenderOptionsFor(options), err);
      parts.world.push_back(&*pictures);
    }
  }
  FlightSetup first;  // the pictures draw its plan
  std::vector<std::unique_ptr<FlightSetup>> members;
  std::vector<std::unique_ptr<CsvOutputs>> csv;
  std::vector<std::unique_ptr<ReportOutputs>> reports;  // one per vehicle, one page for all
  std::optional<RenderOutputs> pictures;
  SwarmParts parts;
};

JsonObject VehicleSummary(const SwarmMember& m, const SwarmSchedule& s, const PlanOutcome& plan,
                          const FlightResult& f, double separation, double vehicle_clearance) {
  JsonObject v;
  v.Add("name", m.name)
      .Add("vehicle", m.vehicle_kind)
      .Add("controller", m.controller.kind)
      .Add("start", Point(plan.start.used))
      .Add("goal", Point(plan.goal.used))
      .Add("flies", s.flies)
      .Add("status", s.flies ? ToString(f.status) : "held its start")
      .Add("note", s.note)
      .Add("delay_s", s.delay)
      .Add("detour", s.detour)
      .Add("trajectory_time_s", s.duration)
      .Add("flight_time_s", f.time)
      .Add("min_separation_m", separation)
      .Add("min_vehicle_clearance_m", vehicle_clearance)
      .Add("replans", f.replans)
      .Add("goals_reached",  // a vehicle that held its start reached none
           s.flies ? static_cast<int>(f.goal_times.size()) +
                         (f.status == FlightStatus::kReachedGoal ? 1 : 0)
                   : 0);
  AddFlightNumbers(f, &v);  // a lone flight's keys
  return v;
}

// The whole flight in a lone flight's keys, as a sweep reads them: the first failure (or
// "reached goal"), the flight's time, the worst vehicle's tracking and the least clearance.
void AddWorst(const FlightSetup& setup, const SwarmMissionResult& r, JsonObject* summary) {
  std::string status = "reached goal", hit;
  double rms = 0.0, clearance = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < r.flight.flights.size(); ++i) {
    const FlightResult& f = r.flight.flights[i];
    const bool failed = !r.schedule[i].flies || f.status != FlightStatus::kReachedGoal;
    if (failed && status == "reached goal") {
      status = r.schedule[i].flies ? ToString(f.status) : "held its start";
      hit = setup.vehicles[i].name + (f.obstacle.empty() ? "" : " with " + f.obstacle);
    }
    rms = std::max(rms, f.rms_error);
    clearance = std::min(clearance, f.min_clearance);
  }
  summary->Add("flight_status", status)
      .Add("flight_time_s", r.flight.time)
      .Add("tracking_rms_m", rms)
      .Add("min_clearance_m", clearance)
      .Add("collision_with", hit);
}

JsonObject SwarmSummary(const FlightSetup& setup, const SwarmMissionResult& r) {
  std::vector<JsonObject> vehicles;
  for (size_t i = 0; i < setup.vehicles.size(); ++i) {
    vehicles.push_back(VehicleSummary(setup.vehicles[i], r.schedule[i], r.plans[i],
                                      r.flight.flights[i], r.flight.vehicle_min_separation[i],
                                      r.flight.vehicle_min_clearance[i]));
  }
  JsonObject swarm;
  swarm.Add("planning", setup.swarm.planning)
      .Add("separation_m", setup.swarm.separation)
      .Add("downwash", setup.swarm.downwash)
      .Add("all_reached", r.AllReached())
      .Add("min_separation_m", r.flight.min_separation)
      .Add("min_separation_time_s", r.flight.min_separation_time)
      .Add("closest_pair", r.flight.closest_pair)
      .Add("makespan_s", r.makespan)
      .Add("flown_makespan_s", r.flown_makespan)
      .Add("alone_makespan_s", r.alone_makespan)
      .Add("flight_time_s", r.flight.time)
      .Add("flight_wall_time_s", r.flight_wall_time);
  JsonObject summary;
  summary.Add("scenario", setup.name)
      .Add("status", r.AllReached() ? "reached goal" : "flight failed")
      .Add("seed", static_cast<long long>(setup.seed))
      .Add("map", setup.map.source);
  AddWorst(setup, r, &summary);
  summary.Add("swarm", swarm).Add("vehicles", vehicles);
  return summary;
}

// The table: a line per vehicle, then the swarm's separation and makespan.
std::string SwarmTable(const OutputFolder& output, const FlightSetup& setup,
                       const FlyOptions& options, const SwarmMissionResult& r) {
  std::ostringstream table;
  table << std::fixed << std::setprecision(3) << "fly " << setup.name << " (seed " << setup.seed
        << ", " << setup.vehicles.size() << " vehicles, planning " << setup.swarm.planning << ")\n";
  for (size_t i = 0; i < setup.vehicles.size(); ++i) {
    const SwarmSchedule& s = r.schedule[i];
    const FlightResult& f = r.flight.flights[i];
    table << "  " << std::left << std::setw(12) << setup.vehicles[i].name << std::right;
    if (!s.flies) {
      table << "held its start: " << s.note << "\n";
      continue;
    }
    table << ToString(f.status) << " after " << f.time << " s";
    if (!f.obstacle.empty()) table << ", hit " << f.obstacle;
    if (s.delay > 0) table << "; waited " << s.delay << " s";
    if (!s.detour.empty()) table << "; bent " << s.detour;
    if (f.replans > 0) table << "; replanned " << f.replans << " time(s)";
    table << "; tracking RMS " << f.rms_error << " m, closest vehicle "
          << r.flight.vehicle_min_separation[i] << " m apart (" << r.flight.vehicle_min_clearance[i]
          << " m clear)\n";
  }
  table << "  separation  " << r.flight.min_separation << " m at least (" << r.flight.closest_pair
        << ", at " << r.flight.min_separation_time << " s)\n"
        << "  makespan    " << r.makespan << " s scheduled, " << r.flown_makespan << " s flown, "
        << r.alone_makespan << " s for the longest flown alone; " << r.flight.time
        << " s of flight in " << r.flight_wall_time << " s wall\n"
        << "  files       " << output.path() << "/<vehicle>/{path,trajectory,telemetry}.csv, "
        << "summary.json" << (options.overview ? ", overview.png" : "")
        << (options.report ? ", report.html" : "") << (options.video ? ", video.mp4" : "") << "\n";
  return table.str();
}

// report.html of every vehicle (a page that cannot be made is a warning: the flights' own files
// are written).
void WriteReport(const std::string& folder, const FlightSetup& setup, const FlyOptions& options,
                 const SwarmOutputs& outputs, const std::string& summary, std::ostream& err) {
  std::vector<const ReportOutputs*> reports;
  std::vector<std::string> names, colours;
  for (size_t i = 0; i < outputs.reports.size(); ++i) {
    reports.push_back(outputs.reports[i].get());
    names.push_back(setup.vehicles[i].name);
    colours.push_back(SwarmRgba(static_cast<int>(i)));
  }
  const std::string command = ReportCommand(options, setup);
  try {
    ReportOutputs::WriteSwarm(folder, setup, reports, names, colours, summary, command);
  } catch (const InputError& e) {
    err << "aerobox: warning: no report.html: " << e.what() << "\n";
  }
}

}  // namespace

int FlySwarmInto(const OutputFolder& output, const FlightSetup& setup, const FlyOptions& options,
                 std::ostream& out, std::ostream& err) {
  SwarmOutputs outputs(output.staging(), setup, options, err);
  if (options.progress) {
    err << "fly " << setup.name << ": planning " << setup.vehicles.size() << " vehicles\n";
  }
  const SwarmMissionResult result = RunSwarm(setup, outputs.parts);
  out << SwarmTable(output, setup, options, result);
  const std::string summary = SwarmSummary(setup, result).Text();
  WriteFileAtomically((fs::path(output.staging()) / "summary.json").string(), summary);
  if (!outputs.reports.empty())
    WriteReport(output.staging(), setup, options, outputs, summary, err);
  return result.AllReached() ? kExitReachedGoal : kExitFlightFailed;
}

}  // namespace aerobox
