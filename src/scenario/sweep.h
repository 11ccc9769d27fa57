// Sweep files: many flights from one file, a product of scenarios, seeds and a grid of scenario
// keys, each run named by a stable id from its parameters.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "common/schema.h"
#include "scenario/scenario.h"

namespace aerobox {

// sweep.toml:
//   name = "speeds"                           # optional; default: the file's stem
//   scenarios = ["scenes/window/scenario.toml", "scenes/m*/scenario.toml"]
//                                             # paths or globs, relative to the sweep file
//   seeds = 5                                 # 1..5; or a list: [1, 2, 7]
//   [grid]                                    # optional: scenario keys and their values
//   "trajectory.max_speed" = [2.0, 4.0]
//   "controller.kind" = ["cascade", "se3"]
//   [keep]                                    # optional: what each run writes beside its
//   video = 0                                 #   summary.json: video.mp4 for the first N runs,
//   telemetry = false                         #   telemetry.csv,
//   overview = false                          #   overview.png,
//   report = false                            #   report.html
inline constexpr int kMaxRuns = 1000000;  // in one sweep

// [keep]: what each run keeps beside its summary.
struct SweepKeep {
  int video = 0;  // runs (in order) that write video.mp4
  bool telemetry = false;
  bool overview = false;
  bool report = false;        // each run's report.html (the sweep writes its own page anyway)
  void Describe(Archive& a);  // common/schema.h
};

struct SweepRun {
  int index = 0;         // in the sweep's order: scenarios, then grid cells, then seeds
  std::string id;        // from the parameters alone: stable across shards, hosts and versions
  std::string scenario;  // the scenario file, as the command opens it
  std::string label;     // the scenario as the sweep names it: relative to the sweep file
  std::uint64_t seed = 1;
  std::vector<Setting> settings;  // the grid cell, in the grid's key order
  bool video = false;
};

struct Sweep {
  std::string file;
  std::string name;
  std::vector<std::string> scenarios;  // resolved, each once, in the order given
  std::vector<std::uint64_t> seeds;
  std::vector<std::pair<std::string, std::vector<std::string>>> grid;  // key, TOML values
  SweepKeep keep;
  std::vector<SweepRun> runs;
};

// Reads and expands a sweep, and loads every run's set-up once, so that a bad key or value is
// reported before anything runs. Throws InputError naming the sweep file's line.
Sweep ReadSweep(const std::string& path);

// 16 hex digits from the scenario label, the seed and the settings.
std::string SweepRunId(const std::string& label, std::uint64_t seed,
                       const std::vector<Setting>& settings);

// A deterministic, disjoint share of the runs: run i belongs to shard i mod count.
struct Shard {
  int index = 0;
  int count = 1;
  bool Contains(const SweepRun& run) const { return run.index % count == index; }
  bool Whole() const { return count == 1; }
};

// "i/N" (0 <= i < N); throws InputError naming `option`.
Shard ParseShard(const std::string& text, const std::string& option);

}  // namespace aerobox
