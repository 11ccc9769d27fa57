// `aerobox compare`: its table's columns come from the trajectories themselves.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/compare_job.h"
#include "app/exit_codes.h"
#include "mission/plan.h"
#include "scenario/scenario.h"
#include "test_support.h"

namespace aerobox {
namespace fs = std::filesystem;
namespace {

// The cells of the table row for `method`, split at '|'.
std::vector<std::string> RowOf(const std::string& table, const std::string& method) {
  std::istringstream lines(table);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.find("| " + method + " |") == std::string::npos) continue;
    std::vector<std::string> cells;
    std::istringstream parts(line);
    std::string cell;
    std::getline(parts, cell, '|');  // before the first '|'
    while (std::getline(parts, cell, '|')) cells.push_back(cell);
    return cells;
  }
  return {};
}

}  // namespace

TEST_CASE("compare: one row per generator, computed from each trajectory") {
  const std::string scenario =
      (testing::SourceDir() / "scenes" / "window" / "scenario.toml").string();
  const testing::TempDir dir;
  std::ostringstream out, progress;
  // the snap objective's times, where the figures below were first measured; the default
  // (min-time) run is checked at the end
  const fs::path snap_scenario = dir.path() / "window_snap.toml";
  {
    std::ofstream file(snap_scenario);
    file << "name = \"window\"\nmap = \""
         << (testing::SourceDir() / "scenes" / "window" / "map.json").string()
         << "\"\n[trajectory]\nobjective = \"snap\"\n";
  }
  REQUIRE(RunCompare({snap_scenario.string()}, dir.path().string(), out, progress) ==
          kExitReachedGoal);
  const std::string table = out.str();
  CAPTURE(table);

  // the same plan as `aerobox fly` makes: the analytic snap cost of its trajectory
  const PlanOutcome plan = PlanFlight(LoadFlightSetup(snap_scenario.string(), {}));
  REQUIRE(plan.trajectory);
  const double snap = plan.trajectory->trajectory.SnapCost();

  const std::vector<std::string> minsnap = RowOf(table, "minsnap");
  const std::vector<std::string> septic = RowOf(table, "septic-full");
  const std::vector<std::string> quintic = RowOf(table, "quintic");
  const std::vector<std::string> cubic = RowOf(table, "cubic");
  REQUIRE(minsnap.size() == 11);
  REQUIRE(septic.size() == 11);
  REQUIRE(quintic.size() == 11);
  REQUIRE(cubic.size() == 11);
  // column 2: integral of snap^2 (Simpson) against the closed-form cost
  CHECK(std::stod(minsnap[2]) == doctest::Approx(snap).epsilon(1e-3));
  CHECK(std::stod(septic[2]) == doctest::Approx(snap).epsilon(1e-3));  // see baselines.h
  CHECK(std::stod(quintic[2]) > 100 * snap);
  CHECK(std::stod(cubic[2]) == 0.0);  // cubic: snap only as impulses at the waypoints ...
  CHECK(std::stod(cubic[4]) > 0.1);   // ... where its jerk jumps
  CHECK(std::stod(quintic[4]) > 1.0);
  CHECK(std::stod(minsnap[4]) < 1e-6);
  for (const auto* row : {&minsnap, &septic, &quintic, &cubic}) {
    CHECK((*row)[9].find("reached goal") != std::string::npos);
  }
  CHECK(testing::ReadFile(dir.path() / "window_profiles.csv").rfind("t,method,x,y,z", 0) == 0);

  // min-time's times: min-snap still has the least snap on them, and every generator flies
  std::ostringstream fast;
  REQUIRE(RunCompare({scenario}, dir.path().string(), fast, progress) == kExitReachedGoal);
  const std::string fast_table = fast.str();
  CAPTURE(fast_table);
  const double fast_snap = std::stod(RowOf(fast_table, "minsnap")[2]);
  CHECK(std::stod(RowOf(fast_table, "quintic")[2]) > 10 * fast_snap);
  CHECK(std::stod(RowOf(fast_table, "septic-full")[2]) == doctest::Approx(fast_snap).epsilon(1e-3));
  for (const char* method : {"minsnap", "septic-full", "quintic", "cubic"}) {
    CHECK(RowOf(fast_table, method)[9].find("reached goal") != std::string::npos);
  }
}

}  // namespace aerobox
