#include "bench/python_benchmark.h"

#include <stdexcept>
#include <utility>
#include <vector>

#include "common/stop.h"
#include "common/subprocess.h"

namespace aerobox {
namespace {

// Runs `argv` (a python and its script) with the build's package on PYTHONPATH, the script's
// table copied to `out`; --smoke added in a smoke run.
void RunScript(std::vector<std::string> argv, const char* what, std::ostream& out,
               const BenchSize& size) {
  ProcessSpec spec;
  spec.argv = std::move(argv);
  if (size.smoke) spec.argv.push_back("--smoke");
  spec.environment = {"PYTHONPATH=" AEROBOX_PYTHON_DIR, "PYTHONDONTWRITEBYTECODE=1"};
  const int code = RunProcess(spec, [&out](const std::string& text) { out << text << std::flush; });
  ThrowIfStopRequested(std::string("running ") + what);
  if (code != 0) throw std::runtime_error(std::string(what) + " failed");
}

}  // namespace

void RunPythonBenchmark(const std::string& window_scenario, std::ostream& out,
                        const BenchSize& size) {
  RunScript(
      {AEROBOX_PYTHON_EXECUTABLE, AEROBOX_PYTHON_BENCH, window_scenario, AEROBOX_PYTHON_TESTS},
      "the Python benchmark (" AEROBOX_PYTHON_BENCH ")", out, size);
}

void RunRotorPyBenchmark(std::ostream& out, const BenchSize& size) {
  RunScript({AEROBOX_PEERS_PYTHON, AEROBOX_ROTORPY_BENCH},
            "the RotorPy benchmark (" AEROBOX_ROTORPY_BENCH " in " AEROBOX_PEERS_PYTHON ")", out,
            size);
}

void RunRlPeers(std::ostream& out, const BenchSize& size) {
  RunScript({AEROBOX_PEERS_PYTHON, AEROBOX_RL_PEERS},
            "the learning peers (" AEROBOX_RL_PEERS " in " AEROBOX_PEERS_PYTHON ")", out, size);
}

}  // namespace aerobox
