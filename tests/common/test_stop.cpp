#include <doctest/doctest.h>

#include <chrono>
#include <string>
#include <thread>

#include "common/stop.h"
#include "common/subprocess.h"

namespace aerobox {

TEST_CASE("the stop flag: nothing thrown until asked, then Interrupted naming the work") {
  CHECK_FALSE(StopRequested());
  CHECK_NOTHROW(ThrowIfStopRequested("idling"));
  int described = 0;
  const auto describe = [&described] {
    ++described;
    return std::string("counting");
  };
  ThrowIfStopRequested(describe);
  CHECK(described == 0);  // the words are only made for a stop
  RequestStop();
  CHECK(StopRequested());
  try {
    ThrowIfStopRequested(describe);
    FAIL("no Interrupted");
  } catch (const Interrupted& stop) {
    CHECK(stop.during() == "counting");
    CHECK(std::string(stop.what()) == "interrupted while counting");
  }
  ClearStopRequest();
  CHECK_FALSE(StopRequested());
}

TEST_CASE("a process: its exit code, its output, and a signal's end as 128 + the signal") {
  ProcessSpec spec;
  spec.argv = {"/bin/sh", "-c", "echo \"$GREETING\"; exit 3"};
  spec.environment = {"GREETING=hello from the child"};
  std::string output;
  CHECK(RunProcess(spec, [&output](const std::string& text) { output += text; }) == 3);
  CHECK(output == "hello from the child\n");
  spec.argv = {"/bin/sh", "-c", "kill -TERM $$"};
  CHECK(RunProcess(spec) == 128 + 15);
  spec.argv = {"/nonexistent/program"};
  CHECK_THROWS_AS(RunProcess(spec), std::runtime_error);
}

TEST_CASE("a stop request reaches the process as SIGINT, at once") {
  ProcessSpec spec;
  spec.argv = {"/bin/sleep", "30"};
  std::thread stopper([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    RequestStop();
  });
  const auto begin = std::chrono::steady_clock::now();
  const int code = RunProcess(spec);
  const double took =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  stopper.join();
  ClearStopRequest();
  CHECK(code == 128 + 2);  // sleep ends by SIGINT
  CHECK(took < 5.0);       // not its 30 s
}

}  // namespace aerobox
