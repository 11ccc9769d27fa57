#include "bench/solver_comparison.h"

#include <benchmark/benchmark.h>

#include <iomanip>
#include <map>
#include <random>
#include <vector>

#include "bench/benchmark_medians.h"
#include "trajectory/min_snap.h"
#include "trajectory/time_allocation.h"

namespace aerobox {
namespace {

// A seeded random walk: segments 1-3 m long turning by up to 90 degrees, as RRT* paths do.
MinSnapProblem RandomProblem(int segments, bool corridors) {
  std::mt19937_64 rng(static_cast<std::uint64_t>(segments));
  std::uniform_real_distribution<double> length(1.0, 3.0);
  std::uniform_real_distribution<double> turn(-M_PI / 2, M_PI / 2);
  std::uniform_real_distribution<double> climb(-0.3, 0.3);
  MinSnapProblem problem;
  problem.waypoints = {Vec3(0, 0, 2)};
  double heading = 0.0;
  for (int i = 0; i < segments; ++i) {
    heading += turn(rng);
    const double l = length(rng);
    problem.waypoints.push_back(problem.waypoints.back() +
                                Vec3(l * std::cos(heading), l * std::sin(heading), climb(rng)));
  }
  problem.durations = TrapezoidDurations(problem.waypoints, 2.0, 2.0);
  if (corridors) {
    // 0.2 m around each straight segment: tight enough that the corners are active
    for (int i = 0; i < segments; ++i) {
      const Vec3& a = problem.waypoints[i];
      const Vec3& b = problem.waypoints[i + 1];
      problem.corridors.push_back(Aabb{a.cwiseMin(b), a.cwiseMax(b)}.Inflated(0.2));
    }
  }
  return problem;
}

// Collects the median real time [ms] of every benchmark, by name.

}  // namespace

void CompareMinSnapSolvers(std::ostream& out, ProgressDisplay& progress, const BenchSize& size) {
  std::vector<int> sizes = {5, 10, 20, 50, 100, 200};
  if (size.smoke) sizes = {5, 10};
  std::map<int, std::string> infeasible;
  for (const int n : sizes) {
    const MinSnapProblem plain = RandomProblem(n, false);
    const MinSnapProblem boxed = RandomProblem(n, true);
    const MinSnapSolution check = SolveMinSnapIpopt(boxed);
    if (check.status != SolveStatus::kSolved) infeasible[n] = check.message;
    const auto add = [&](const std::string& name, auto solve) {
      Sized(benchmark::RegisterBenchmark(name.c_str(),
                                         [solve](benchmark::State& state) {
                                           for (auto _ : state) benchmark::DoNotOptimize(solve());
                                         })
                ->Unit(benchmark::kMillisecond),
            size, 5, 0.2);
    };
    add("closed/" + std::to_string(n), [plain] { return SolveMinSnapClosedForm(plain); });
    add("ipopt/" + std::to_string(n), [plain] { return SolveMinSnapIpopt(plain); });
    add("corridors/" + std::to_string(n), [boxed] { return SolveMinSnapIpopt(boxed); });
    // the time refinement (20 steps), with the envelope gradient and, up to 100 segments, with
    // finite differences of the whole solve
    add("refine/" + std::to_string(n),
        [plain] { return RefineDurations(plain.waypoints, plain.durations, 20); });
    if (n <= 100) {
      add("refine_fd/" + std::to_string(n), [plain] {
        return RefineDurations(plain.waypoints, plain.durations, 20,
                               DurationGradient::kFiniteDifferences);
      });
    }
  }
  progress.Show("timing min-snap solvers ...", true);
  const std::map<std::string, double> medians = RunRegisteredBenchmarks();
  progress.Clear();

  out << "| segments | closed form [ms] | Ipopt, equalities [ms] | ratio | Ipopt, corridors [ms] "
         "| ratio |\n|---|---|---|---|---|---|\n"
      << std::fixed;
  for (const int n : sizes) {
    const std::string key = std::to_string(n);
    const double closed = medians.at("closed/" + key);
    const double ipopt = medians.at("ipopt/" + key);
    const double boxed = medians.at("corridors/" + key);
    out << "| " << n << " | " << std::setprecision(3) << closed << " | " << ipopt << " | "
        << std::setprecision(2) << ipopt / closed << " | " << std::setprecision(3) << boxed
        << (infeasible.count(n) ? " (" + infeasible[n] + ")" : std::string()) << " | "
        << std::setprecision(2) << boxed / closed << " |\n";
  }
  out << "\nTime refinement, 20 gradient steps with line search:\n\n"
      << "| segments | envelope gradient [ms] | finite differences [ms] | ratio |\n"
      << "|---|---|---|---|\n";
  for (const int n : sizes) {
    const std::string key = std::to_string(n);
    const double envelope = medians.at("refine/" + key);
    out << "| " << n << " | " << std::setprecision(3) << envelope << " | ";
    if (medians.count("refine_fd/" + key)) {
      const double differences = medians.at("refine_fd/" + key);
      out << differences << " | " << std::setprecision(3) << envelope / differences << " |\n";
    } else {
      out << "(not run: minutes) | |\n";
    }
  }
}

}  // namespace aerobox
