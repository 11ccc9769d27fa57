#include "app/compare_job.h"

#include <chrono>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "app/exit_codes.h"
#include "geometry/collision_world.h"
#include "mission/flight.h"
#include "mission/plan.h"
#include "outputs/files.h"
#include "scenario/scenario.h"
#include "telemetry/csv_table.h"

namespace aerobox {
namespace {

constexpr TrajectoryMethod kMethods[] = {TrajectoryMethod::kMinSnap, TrajectoryMethod::kSepticFull,
                                         TrajectoryMethod::kQuintic, TrajectoryMethod::kCubic};

// integral of |d^r p / dt^r|^2 over the trajectory, Simpson's rule, 200 intervals a segment
double IntegratedSquare(const PiecewiseTrajectory& trajectory, int derivative) {
  constexpr int kIntervals = 200;
  double total = 0.0;
  for (const PolynomialSegment& segment : trajectory.segments()) {
    const double h = segment.duration() / kIntervals;
    for (int i = 0; i <= kIntervals; ++i) {
      const double w = (i == 0 || i == kIntervals) ? 1 : (i % 2 == 1 ? 4 : 2);
      total += w * h / 3.0 * segment.Evaluate3(i * h, derivative).squaredNorm();
    }
  }
  return total;
}

// The largest jump of the jerk at a waypoint [m/s^3]: where it jumps, snap is an impulse that
// the integral inside the segments does not see.
double LargestJerkJump(const PiecewiseTrajectory& trajectory) {
  const std::vector<PolynomialSegment>& s = trajectory.segments();
  double largest = 0.0;
  for (size_t i = 0; i + 1 < s.size(); ++i) {
    largest = std::max(
        largest, (s[i].Evaluate3(s[i].duration(), kJerk) - s[i + 1].Evaluate3(0.0, kJerk)).norm());
  }
  return largest;
}

struct Row {
  std::string method;
  double snap = 0, jerk = 0, jerk_jump = 0, max_speed = 0, max_accel = 0, saturated = 0, rms = 0,
         solve = 0;
  std::string outcome;
};

Row FlyMethod(const FlightSetup& setup, const PlanOutcome& plan, TrajectoryMethod method,
              const CollisionWorld& world) {
  Row row;
  row.method = ToString(method);
  PiecewiseTrajectory trajectory = plan.trajectory->trajectory;
  row.solve = plan.trajectory->stats.solve_time;
  if (method != TrajectoryMethod::kMinSnap) {
    const auto begin = std::chrono::steady_clock::now();
    trajectory =
        BaselineTrajectory(method, plan.trajectory->waypoints, trajectory.SegmentDurations());
    row.solve = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  }
  row.snap = IntegratedSquare(trajectory, kSnap);
  row.jerk = IntegratedSquare(trajectory, kJerk);
  row.jerk_jump = LargestJerkJump(trajectory);
  row.max_speed = trajectory.MaxNorm(kVelocity, 0.01);
  row.max_accel = trajectory.MaxNorm(kAcceleration, 0.01);

  Simulation sim = Simulation::FromXml(SceneMjcfFor(setup), setup.name + " (scene)");
  const QuadParams& vehicle = setup.vehicle;
  PlaceVehicleAtStart(setup.map, vehicle, setup.start, plan.start.used, &sim);
  const FlightResult flight = FlyTrajectory(
      ReferenceOf(trajectory), setup.flight, vehicle, setup.controller,
      [&world](const Vec3& p) { return world.Clearance(p); }, {}, &sim);
  // a rotor at either end of its range: the mixer has no authority left there
  row.saturated = flight.saturated_time;
  row.rms = flight.rms_error;
  row.outcome = ToString(flight.status);
  if (!flight.obstacle.empty()) row.outcome += " (" + flight.obstacle + ")";
  return row;
}

std::string ProfilesCsv(const PlanOutcome& plan) {
  CsvTable table({"t", "method", "x", "y", "z", "ax", "ay", "az"});
  const std::vector<double> durations = plan.trajectory->trajectory.SegmentDurations();
  for (const TrajectoryMethod method : kMethods) {
    const PiecewiseTrajectory trajectory =
        method == TrajectoryMethod::kMinSnap
            ? plan.trajectory->trajectory
            : BaselineTrajectory(method, plan.trajectory->waypoints, durations);
    for (double t = 0.0; t <= trajectory.duration(); t += 0.02) {
      Eigen::Matrix<double, 8, 1> values;
      values << t, static_cast<double>(static_cast<int>(method)),
          trajectory.Evaluate3(t, kPosition), trajectory.Evaluate3(t, kAcceleration);
      table.AddRow(values);
    }
  }
  return table.Text();
}

}  // namespace

int RunCompare(const std::vector<std::string>& scenarios, const std::string& out_dir,
               std::ostream& out, std::ostream& progress) {
  std::vector<FlightSetup> setups;  // every file is read before any work
  for (const std::string& scenario : scenarios) {
    setups.push_back(LoadFlightSetup(scenario, {}));
    if (!setups.back().vehicles.empty()) {
      throw InputError({scenario, setups.back().vehicles.front().where.line}, "vehicles",
                       "compare flies one vehicle's route; this scenario has several");
    }
  }
  OutputFolder output(out_dir, "compare");
  const std::string& folder = output.staging();
  out << "| map | generator | integral snap^2 [m^2/s^7] | integral jerk^2 [m^2/s^5] | largest "
         "jerk jump [m/s^3] | max speed [m/s] | max accel [m/s^2] | rotors saturated [s] | "
         "tracking RMS [m] | flight | solve [ms] "
         "|\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const FlightSetup& setup : setups) {
    progress << "compare: " << setup.name << "\n" << std::flush;
    const PlanOutcome plan = PlanFlight(setup);
    if (plan.result.status != PlanStatus::kSolved || !plan.trajectory ||
        plan.trajectory->status != TrajectoryStatus::kSolved) {
      out << "| " << setup.name << " | (no path or trajectory) | | | | | | | | | |\n";
      continue;
    }
    const CollisionWorld world(setup.map, CollisionParams{setup.vehicle.collision_size, 0.0});
    for (const TrajectoryMethod method : kMethods) {
      const Row row = FlyMethod(setup, plan, method, world);
      out << std::setprecision(4) << "| " << setup.name << " | " << row.method << " | " << row.snap
          << " | " << row.jerk << " | " << row.jerk_jump << " | " << std::fixed
          << std::setprecision(2) << row.max_speed << " | " << row.max_accel << " | "
          << row.saturated << " | " << std::setprecision(3) << row.rms << " | " << row.outcome
          << " | " << std::setprecision(2) << 1e3 * row.solve << " |\n"
          << std::defaultfloat;
    }
    output.Run([&] {
      WriteFileAtomically((std::filesystem::path(folder) / (setup.name + "_profiles.csv")).string(),
                          ProfilesCsv(plan));
    });
  }
  output.Commit();
  out << "\nMethods in the profiles CSVs: 0 minsnap, 1 quintic, 2 cubic, 3 septic-full.\n";
  return kExitReachedGoal;
}

}  // namespace aerobox
