// The bad-input corpus (tests/bad_inputs): malformed maps and scenarios of every format. Each
// must end with exit code 2, a message naming the file and the line at fault, and no output.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/exit_codes.h"
#include "cli_runner.h"
#include "common/error.h"
#include "scenario/scenario.h"
#include "test_support.h"

namespace aerobox {

TEST_CASE("every malformed input exits 2, names its file and line, and writes nothing") {
  const std::filesystem::path folder = testing::SourceDir() / "tests" / "bad_inputs";
  std::ifstream manifest(folder / "expected_lines.txt");
  REQUIRE(manifest);
  std::string line;
  int cases = 0;
  while (std::getline(manifest, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string name;
    int expected_line = 0;
    REQUIRE(static_cast<bool>(fields >> name >> expected_line));
    ++cases;
    const std::string input = (folder / name).string();
    CAPTURE(input);
    const testing::TempDir dir;
    const std::string out_dir = (dir.path() / "out").string();
    const testing::CliRun run =
        testing::RunAerobox({"fly", input, "--no-video", "--quiet", "--out", out_dir});
    CAPTURE(run.err);
    CHECK(run.code == kExitBadInput);
    CHECK(run.err.find(input + ":" + std::to_string(expected_line) + ": ") != std::string::npos);
    CHECK(run.err.find('\0') == std::string::npos);  // binary junk is escaped
    CHECK_FALSE(std::filesystem::exists(out_dir));
  }
  // every file of the corpus is listed
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    files += entry.path().filename() != "expected_lines.txt";
  }
  CHECK(cases == files);
  CHECK(cases >= 30);
}

}  // namespace aerobox

namespace aerobox {

TEST_CASE("the scenario fuzzer's kept inputs read without a crash") {
  const std::filesystem::path corpus =
      testing::SourceDir() / "tests" / "fuzz" / "corpus" / "scenario";
  int inputs = 0;
  for (const auto& entry : std::filesystem::directory_iterator(corpus)) {
    CAPTURE(entry.path());
    std::ifstream in(entry.path(), std::ios::binary);
    try {
      const Scenario scenario = ReadScenario(in, "corpus.toml");
      CHECK_FALSE(scenario.map_path.empty());
      CHECK_NOTHROW(scenario.planning.trajectory.Validate());
    } catch (const InputError&) {
      // the expected answer to bad input
    }
    ++inputs;
  }
  CHECK(inputs >= 5);
}

}  // namespace aerobox
