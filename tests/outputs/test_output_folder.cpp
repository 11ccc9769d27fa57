#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

#include "common/error.h"
#include "outputs/files.h"

namespace aerobox {
namespace fs = std::filesystem;
namespace {

std::string Read(const fs::path& file) {
  std::ifstream in(file);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// A temporary folder of this process, removed at the end of the test.
struct Scratch {
  fs::path path = fs::temp_directory_path() / ("aerobox_folder_test_" + std::to_string(getpid()));
  Scratch() { fs::remove_all(path); }
  ~Scratch() { fs::remove_all(path); }
};

// Writes a run of `files` (name -> text) into `folder`, committed or not.
void Run(const fs::path& folder, const std::map<std::string, std::string>& files, bool commit) {
  OutputFolder output(folder.string(), "unused");
  for (const auto& [name, text] : files) {
    WriteFileAtomically((fs::path(output.staging()) / name).string(), text);
  }
  // nothing of this run is in the folder before it commits
  for (const auto& [name, text] : files) CHECK(Read(folder / name) != text);
  if (commit) output.Commit();
}

}  // namespace

TEST_CASE("an output folder holds one whole run: the earlier one until the next commits") {
  Scratch scratch;
  const fs::path folder = scratch.path / "run";
  Run(folder, {{"path.csv", "first path"}, {"telemetry.csv", "first telemetry"}}, true);
  CHECK(Read(folder / "path.csv") == "first path");
  CHECK(Read(folder / "telemetry.csv") == "first telemetry");

  SUBCASE("a run that does not commit (a failure, Ctrl-C) leaves the earlier run as it was") {
    Run(folder, {{"path.csv", "second path"}}, false);
    CHECK(Read(folder / "path.csv") == "first path");
    CHECK(Read(folder / "telemetry.csv") == "first telemetry");
  }
  SUBCASE("a run that commits replaces the earlier run whole, its other files included") {
    std::ofstream(folder / "notes.txt") << "the user's own file";
    Run(folder, {{"path.csv", "second path"}}, true);
    CHECK(Read(folder / "path.csv") == "second path");
    CHECK_FALSE(fs::exists(folder / "telemetry.csv"));           // the earlier run's
    CHECK(Read(folder / "notes.txt") == "the user's own file");  // not aerobox's: kept
  }
  // no staging folder or lock is left either way
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    CHECK(entry.path().filename().string().rfind(".aerobox-staging", 0) != 0);
    CHECK(entry.path().filename() != ".aerobox.lock");
  }
}

TEST_CASE("a run that made its folder and did not commit leaves no folder") {
  Scratch scratch;
  const fs::path folder = scratch.path / "new";
  Run(folder, {{"path.csv", "a path"}}, false);
  CHECK_FALSE(fs::exists(folder));
}

TEST_CASE("a second run into a locked folder is refused before it writes") {
  Scratch scratch;
  const fs::path folder = scratch.path / "busy";
  const OutputFolder first(folder.string(), "unused");
  CHECK_THROWS_AS(OutputFolder(folder.string(), "unused"), InputError);
}

}  // namespace aerobox

namespace aerobox {

TEST_CASE("the one file lock: a second holder is refused naming the first, and it is released") {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("aerobox-lock-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "x.lock").string();
  {
    const FileLock first(path, dir.string(), "--out", "another holder", "holds it");
    CHECK(std::filesystem::exists(path));
    CHECK_THROWS_WITH_AS(FileLock(path, dir.string(), "--out", "another holder", "holds it"),
                         (dir.string() + ": --out: another holder (process " +
                          std::to_string(getpid()) + ") holds it")
                             .c_str(),
                         InputError);
  }
  CHECK_FALSE(std::filesystem::exists(path));  // released and removed
  CHECK_NOTHROW(FileLock(path, dir.string(), "--out", "another holder", "holds it"));
  std::filesystem::remove_all(dir);
}

}  // namespace aerobox
