#include "bench/python_benchmark.h"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <stdexcept>

#include "common/quoting.h"

namespace aerobox {

void RunPythonBenchmark(const std::string& window_scenario, std::ostream& out) {
  const std::string command =
      "PYTHONPATH=" + ShellQuoted(AEROBOX_PYTHON_DIR) + " PYTHONDONTWRITEBYTECODE=1 " +
      ShellQuoted(AEROBOX_PYTHON_EXECUTABLE) + " " + ShellQuoted(AEROBOX_PYTHON_BENCH) + " " +
      ShellQuoted(window_scenario) + " " + ShellQuoted(AEROBOX_PYTHON_TESTS);
  std::FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) throw std::runtime_error("cannot start " AEROBOX_PYTHON_EXECUTABLE);
  std::array<char, 4096> buffer{};
  size_t read = 0;
  while ((read = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) {
    out.write(buffer.data(), static_cast<std::streamsize>(read));
    out.flush();
  }
  const int status = pclose(pipe);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error("the Python benchmark (" AEROBOX_PYTHON_BENCH ") failed");
  }
}

}  // namespace aerobox
