#include <filesystem>
#include <fstream>
#include <set>

#include "scenario/sweep.h"
#include "test_support.h"

namespace aerobox {
namespace {

namespace fs = std::filesystem;

// A sweep file in a fresh folder; its scenarios are the repository's scenes.
std::string WriteSweep(const std::string& name, const std::string& text) {
  const fs::path folder = fs::temp_directory_path() / "aerobox_test_sweep";
  fs::create_directories(folder);
  const fs::path file = folder / (name + ".toml");
  std::ofstream(file) << text;
  return file.string();
}

std::string Scenes() { return (testing::SourceDir() / "scenes").string(); }

}  // namespace

TEST_CASE("a sweep is scenarios x grid cells x seeds, in that order, each run with its id") {
  const Sweep sweep = ReadSweep(WriteSweep("order", "scenarios = [\"" + Scenes() +
                                                        "/window/scenario.toml\", \"" + Scenes() +
                                                        "/m*e/scenario.toml\"]\n"
                                                        "seeds = [3, 7]\n"
                                                        "[grid]\n"
                                                        "\"trajectory.max_speed\" = [2.0, 4]\n"
                                                        "\"controller.kind\" = [\"cascade\", "
                                                        "\"se3\"]\n"
                                                        "[keep]\nvideo = 3\n"));
  REQUIRE(sweep.scenarios.size() == 2);  // window, and maze from the glob
  CHECK(fs::path(sweep.scenarios[1]).parent_path().filename() == "maze");
  REQUIRE(sweep.runs.size() == 2 * 4 * 2);
  // the first grid key varies slowest, the seed fastest
  CHECK(sweep.runs[0].seed == 3);
  CHECK(sweep.runs[1].seed == 7);
  REQUIRE(sweep.runs[0].settings.size() == 2);
  CHECK(sweep.runs[0].settings[0].key == "controller.kind");  // the grid's keys, sorted
  CHECK(sweep.runs[0].settings[0].value == "\"cascade\"");
  CHECK(sweep.runs[0].settings[1].value == "2.0");
  CHECK(sweep.runs[2].settings[1].value == "4");  // an integer stays one
  CHECK(sweep.runs[4].settings[0].value == "\"se3\"");
  CHECK(sweep.runs[8].scenario == sweep.scenarios[1]);
  std::set<std::string> ids;
  for (size_t i = 0; i < sweep.runs.size(); ++i) {
    CHECK(sweep.runs[i].index == static_cast<int>(i));
    CHECK(sweep.runs[i].video == (i < 3));
    ids.insert(sweep.runs[i].id);
  }
  CHECK(ids.size() == sweep.runs.size());
  // an id comes from the parameters only: the same sweep read again, the same ids
  const Sweep again = ReadSweep(WriteSweep("order_again", "scenarios = [\"" + Scenes() +
                                                              "/window/scenario.toml\"]\n"
                                                              "seeds = [7]\n"
                                                              "[grid]\n"
                                                              "\"trajectory.max_speed\" = [4]\n"
                                                              "\"controller.kind\" = [\"se3\"]\n"));
  CHECK(again.runs.front().id == sweep.runs[7].id);
}

TEST_CASE("shards: every run in exactly one, whatever their number") {
  const Sweep sweep = ReadSweep(WriteSweep(
      "shards", "scenarios = [\"" + Scenes() + "/window/scenario.toml\"]\nseeds = 23\n"));
  REQUIRE(sweep.runs.size() == 23);
  for (int count = 1; count <= 30; ++count) {
    std::vector<int> owners(sweep.runs.size(), 0);
    for (int i = 0; i < count; ++i) {
      for (const SweepRun& run : sweep.runs) owners[run.index] += Shard{i, count}.Contains(run);
    }
    for (const int n : owners) CHECK(n == 1);
  }
  CHECK(ParseShard("2/4", "--shard").index == 2);
  CHECK_THROWS_AS(ParseShard("4/4", "--shard"), InputError);
  CHECK_THROWS_AS(ParseShard("1", "--shard"), InputError);
  CHECK_THROWS_AS(ParseShard("-1/3", "--shard"), InputError);
}

TEST_CASE("a bad sweep file names its line before anything runs") {
  const auto line_of = [](const std::string& name, const std::string& text) {
    try {
      ReadSweep(WriteSweep(name, text));
    } catch (const InputError& e) {
      MESSAGE(e.what());
      return e.where().line;
    }
    return -1;
  };
  const std::string window = "scenarios = [\"" + Scenes() + "/window/scenario.toml\"]\n";
  CHECK(line_of("unknown", window + "seedz = 3\n") == 2);
  CHECK(line_of("empty_grid", window + "[grid]\n") == 2);
  CHECK(line_of("empty_values", window + "[grid]\n\"trajectory.max_speed\" = []\n") == 3);
  CHECK(line_of("glob", "scenarios = [\"nowhere/*.toml\"]\n") == 1);
  CHECK(line_of("not_scenario", "scenarios = [\"" + Scenes() + "/window/map.json\"]\n") == 1);
  CHECK(line_of("key", window + "[grid]\n\"trajectory.max_sped\" = [1.0]\n") == 3);
  CHECK(line_of("value", window + "[grid]\n\"trajectory.max_speed\" = [1.0, 99.0]\n") == 3);
  CHECK(line_of("seed_in_grid", window + "[grid]\nseed = [1, 2]\n") == 3);
  CHECK(line_of("twice", window + "seeds = [1, 2, 1]\n") == 2);
  CHECK(line_of("keep", window + "[keep]\nvideos = 1\n") == 3);
  CHECK(line_of("missing", "seeds = 2\n") == 1);
  // [keep] is read through SweepKeep's Describe: a misspelt key or a value out of range is
  // named as in a scenario
  const auto error_of = [](const std::string& name, const std::string& text) {
    try {
      ReadSweep(WriteSweep(name, text));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK(
      error_of("keep_typo", window + "[keep]\nvideos = 1\n")
          .find("keep.videos: unknown key (expected video, telemetry, overview or report); did you "
                "mean video?") != std::string::npos);
  CHECK(error_of("keep_range", window + "[keep]\nvideo = -1\n")
            .find("keep.video: expected a whole number from 0 to 1000000") != std::string::npos);
  CHECK(error_of("top_typo", window + "seedz = 3\n").find("did you mean seeds?") !=
        std::string::npos);
}

}  // namespace aerobox
