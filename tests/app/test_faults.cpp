// Faults (docs/reliability.md): an output folder that cannot be made, a failing write, a
// non-finite value in the controller and an Ipopt failure, the last three injected through
// AEROBOX_FAULT (common/fault_injection.h). Each ends with its exit code, a clear message and
// no partial file.
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/exit_codes.h"
#include "cli_runner.h"
#include "summary_json.h"
#include "test_support.h"

namespace aerobox {
namespace {

// `aerobox fly window --no-video --out OUT` with AEROBOX_FAULT set to `fault` (when not empty).
testing::CliRun FlyWindow(const std::string& out_dir, const std::string& fault) {
  const std::string scenario =
      (testing::SourceDir() / "scenes" / "window" / "scenario.toml").string();
  if (!fault.empty()) setenv("AEROBOX_FAULT", fault.c_str(), 1);
  const testing::CliRun run =
      testing::RunAerobox({"fly", scenario, "--no-video", "--quiet", "--out", out_dir});
  unsetenv("AEROBOX_FAULT");
  return run;
}

bool HasPartialFiles(const std::filesystem::path& folder) {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    if (entry.path().extension() == ".partial") return true;
  }
  return false;
}

}  // namespace

TEST_CASE("an output folder that cannot be made stops the run before any work") {
  const testing::TempDir dir;
  std::ofstream(dir.path() / "a_file") << "x";
  const testing::CliRun run = FlyWindow((dir.path() / "a_file" / "out").string(), "");
  CHECK(run.code == kExitBadInput);
  CHECK(run.err.find("--out: cannot create the output folder") != std::string::npos);
  CHECK(run.out.empty());  // nothing planned or flown
}

TEST_CASE("a failing write: a clear error, exit 2, and no partial file") {
  for (const char* name : {"path.csv", "trajectory.csv", "telemetry.csv", "summary.json"}) {
    CAPTURE(name);
    const testing::TempDir dir;
    const std::filesystem::path out = dir.path() / "out";
    const testing::CliRun run = FlyWindow(out.string(), std::string("write:") + name);
    CAPTURE(run.err);
    CHECK(run.code == kExitBadInput);
    CHECK(run.err.find((out / name).string() + ": writing failed") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(out / name));
    CHECK_FALSE(HasPartialFiles(out));
  }
}

TEST_CASE("a non-finite value in the controller: status non-finite, exit 5") {
  const testing::TempDir dir;
  const std::filesystem::path out = dir.path() / "out";
  const testing::CliRun run = FlyWindow(out.string(), "nonfinite:3");
  CHECK(run.code == kExitFlightFailed);
  CHECK(run.out.find("non-finite state after 3.0") != std::string::npos);
  CHECK(testing::ReadSummary(out / "summary.json")["flight_status"] == "non-finite state");
  CHECK_FALSE(HasPartialFiles(out));
}

TEST_CASE(
    "an Ipopt failure: the closed form takes over, and without it exit 4 with Ipopt's reason") {
  const testing::TempDir dir;
  const std::filesystem::path out = dir.path() / "out";
  // by default the closed form with refinement takes over, and says why
  const testing::CliRun fallback = FlyWindow(out.string(), "ipopt");
  CHECK(fallback.code == kExitReachedGoal);
  CHECK(fallback.out.find("(closed form with refinement, after Ipopt: maximum iterations "
                          "exceeded; the closed form flown instead passed the same checks") !=
        std::string::npos);
  // and summary.json says it, so that a sweep can count it
  const auto summary = testing::ReadSummary(out / "summary.json");
  CHECK(summary["trajectory_fallback"] == true);
  CHECK(summary["trajectory_solver_message"] ==
        "closed form with refinement, after Ipopt: maximum iterations exceeded");
  const std::string window = (testing::SourceDir() / "scenes" / "window" / "map.json").string();
  const std::string scenario =
      dir.Write("strict.toml", "name = \"window\"\nmap = \"" + window +
                                   "\"\n[trajectory]\nclosed_form_fallback = false\n");
  const std::filesystem::path strict_out = dir.path() / "strict";
  setenv("AEROBOX_FAULT", "ipopt", 1);
  const testing::CliRun run =
      testing::RunAerobox({"fly", scenario, "--no-video", "--quiet", "--out", strict_out.string()});
  unsetenv("AEROBOX_FAULT");
  CHECK(run.code == kExitNoTrajectory);
  CHECK(run.out.find("no trajectory (maximum iterations exceeded)") != std::string::npos);
  CHECK(testing::ReadSummary(strict_out / "summary.json")["status"] == "no feasible trajectory");
  CHECK_FALSE(std::filesystem::exists(strict_out / "telemetry.csv"));
  CHECK_FALSE(HasPartialFiles(strict_out));
}

}  // namespace aerobox
