// Collects Google Benchmark's median aggregates by benchmark name, for the tables of
// `aerobox bench` (each section registers its benchmarks, runs them, and reads the medians).
#pragma once

#include <benchmark/benchmark.h>

#include <map>
#include <string>
#include <vector>

namespace aerobox {

class MedianCollector : public benchmark::BenchmarkReporter {
 public:
  bool ReportContext(const Context&) override { return true; }
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.aggregate_name == "median")
        medians[run.run_name.function_name] = run.GetAdjustedRealTime();
    }
  }
  // median real time per iteration, in each benchmark's unit, by name
  std::map<std::string, double> medians;
};

// Runs every registered benchmark, clears the registry, and returns the medians.
inline std::map<std::string, double> RunRegisteredBenchmarks() {
  MedianCollector collector;
  benchmark::RunSpecifiedBenchmarks(&collector);
  benchmark::ClearRegisteredBenchmarks();
  return collector.medians;
}

}  // namespace aerobox
