#include "bench/sweep_benchmark.h"

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <stdexcept>

#include "common/quoting.h"
#include "common/stop.h"
#include "common/subprocess.h"

namespace aerobox {
namespace fs = std::filesystem;
namespace {

// Wall time of one `aerobox sweep` [s].
double TimeSweep(const std::string& binary, const fs::path& sweep, const fs::path& out, int jobs) {
  fs::remove_all(out);
  ProcessSpec spec;
  spec.argv = {binary,       "sweep", sweep.string(),       "--out",
               out.string(), "-j",    std::to_string(jobs), "--quiet"};
  spec.output = "/dev/null";
  const auto begin = std::chrono::steady_clock::now();
  const int code = RunProcess(spec);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  ThrowIfStopRequested("timing aerobox sweep (its finished runs are in " + out.string() + ")");
  if (code != 0) {
    throw std::runtime_error("aerobox sweep failed (exit " + std::to_string(code) +
                             "): " + ShellQuoted(binary) + " sweep " + ShellQuoted(sweep.string()));
  }
  return wall;
}

}  // namespace

void SweepBenchmark(const std::string& window_scenario, int seeds, std::ostream& out,
                    ProgressDisplay& progress) {
  const fs::path binary = fs::read_symlink("/proc/self/exe").parent_path() / "aerobox";
  if (!fs::exists(binary)) throw std::runtime_error(binary.string() + " is missing");
  const fs::path work =
      fs::temp_directory_path() / ("aerobox_sweep_bench_" + std::to_string(getpid()));
  fs::create_directories(work);
  const fs::path sweep = work / "speeds.toml";
  std::ofstream(sweep) << "scenarios = [\"" << fs::absolute(window_scenario).string() << "\"]\n"
                       << "seeds = " << seeds << "\n[grid]\n"
                       << "\"trajectory.max_speed\" = [1.0, 2.0, 3.0, 4.0, 5.0]\n";
  const int runs = 5 * seeds;
  progress.Show("sweep: " + std::to_string(runs) + " runs with -j 1 ...", true);
  const double one = TimeSweep(binary.string(), sweep, work / "j1", 1);
  progress.Show("sweep: " + std::to_string(runs) + " runs with -j 2 ...", true);
  const double two = TimeSweep(binary.string(), sweep, work / "j2", 2);
  progress.Clear();
  fs::remove_all(work);
  out << std::fixed << std::setprecision(2) << "| processes | wall time [s] | runs per second |\n"
      << "|---|---|---|\n"
      << "| -j 1 | " << one << " | " << runs / one << " |\n"
      << "| -j 2 | " << two << " | " << runs / two << " |\n\n"
      << "Throughput of -j 2 against -j 1: " << one / two << "x (" << runs << " runs: the window, "
      << seeds << " seeds x 5 speed limits, no video)\n"
      << std::defaultfloat;
}

}  // namespace aerobox
