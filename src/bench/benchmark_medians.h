// Collects Google Benchmark's median aggregates by benchmark name, for the tables of
// `aerobox bench` (each section registers its benchmarks, runs them, and reads the medians).
#pragma once

#include <benchmark/benchmark.h>

#include <map>
#include <string>
#include <vector>

namespace aerobox {

// How big each section's runs are: the full tables, or a smoke run (`aerobox bench --smoke`, in
// tools/test.sh) that only shows every section still runs end to end: one repetition, the
// smallest sizes, numbers that mean nothing.
struct BenchSize {
  bool smoke = false;
  int Repetitions(int full) const { return smoke ? 1 : full; }
  // [s] Google Benchmark's minimum time per repetition
  double MinTime(double full) const { return smoke ? 1e-3 : full; }
  int Count(int full, int in_smoke) const { return smoke ? in_smoke : full; }
};

// A registered benchmark at `size`: `repetitions` (medians reported), at least `min_time` [s]
// each (0: Google Benchmark's own default).
inline void Sized(benchmark::internal::Benchmark* b, const BenchSize& size, int repetitions,
                  double min_time = 0.0) {
  b->Repetitions(size.Repetitions(repetitions))->ReportAggregatesOnly(true);
  if (min_time > 0 || size.smoke) b->MinTime(size.MinTime(min_time));
}

class MedianCollector : public benchmark::BenchmarkReporter {
 public:
  bool ReportContext(const Context&) override { return true; }
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      const std::string& name = run.run_name.function_name;
      // one repetition has no aggregates: its one run is the median
      if (run.aggregate_name == "median" ||
          (run.run_type == Run::RT_Iteration && medians.count(name) == 0)) {
        medians[name] = run.GetAdjustedRealTime();
      }
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
