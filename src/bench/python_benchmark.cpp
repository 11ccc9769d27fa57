#include "bench/python_benchmark.h"

#include <stdexcept>

#include "common/stop.h"
#include "common/subprocess.h"

namespace aerobox {

void RunPythonBenchmark(const std::string& window_scenario, std::ostream& out,
                        const BenchSize& size) {
  ProcessSpec spec;
  spec.argv = {AEROBOX_PYTHON_EXECUTABLE, AEROBOX_PYTHON_BENCH, window_scenario,
               AEROBOX_PYTHON_TESTS};
  if (size.smoke) spec.argv.push_back("--smoke");
  spec.environment = {"PYTHONPATH=" AEROBOX_PYTHON_DIR, "PYTHONDONTWRITEBYTECODE=1"};
  const int code = RunProcess(spec, [&out](const std::string& text) { out << text << std::flush; });
  ThrowIfStopRequested("running the Python benchmark");
  if (code != 0) {
    throw std::runtime_error("the Python benchmark (" AEROBOX_PYTHON_BENCH ") failed");
  }
}

}  // namespace aerobox
