#include "bench/planner_comparison.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>

#include "planning/rrt_star.h"

namespace aerobox {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double Median(std::vector<double> values) {
  if (values.empty()) return kInf;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::string Show(double value, int decimals) {
  if (!std::isfinite(value)) return "none";
  std::ostringstream text;
  text << std::fixed << std::setprecision(decimals) << value;
  return text.str();
}

struct Summary {
  double first_ms;    // median time to first solution [ms] (unsolved runs count as infinite)
  double cost_early;  // median cost at 0.2 s [m]
  double cost_end;    // median cost at the end [m]
  double simplified;  // median cost after simplification [m]
  double iterations;  // median number of iterations
  int solved;
};

Summary Summarize(const std::vector<AnytimeRun>& runs, double seconds) {
  std::vector<double> first, early, end, simplified, iterations;
  int solved = 0;
  for (const AnytimeRun& run : runs) {
    first.push_back(run.time_to_first >= 0 ? 1e3 * run.time_to_first : kInf);
    early.push_back(run.CostAt(0.2));
    end.push_back(run.CostAt(seconds));
    simplified.push_back(run.simplified_cost >= 0 ? run.simplified_cost : kInf);
    iterations.push_back(static_cast<double>(run.iterations));
    solved += run.time_to_first >= 0;
  }
  return {Median(first),      Median(early),      Median(end),
          Median(simplified), Median(iterations), solved};
}

}  // namespace

double AnytimeRun::CostAt(double t) const {
  double best = kInf;
  for (const auto& [time, cost] : history) {
    if (time <= t) best = std::min(best, cost);
  }
  return best;
}

AnytimeRun RunOurs(const CollisionWorld& world, const PlanningProblem& problem, double seconds,
                   std::uint64_t seed) {
  RrtStarParams params;
  params.time_budget = seconds;
  params.seed = seed;
  const Validity validity{
      [&world](const Vec3& p) { return world.IsPointFree(p); },
      [&world](const Vec3& a, const Vec3& b) { return world.IsSegmentFree(a, b); }};
  const PlanResult result =
      PlanRrtStar(problem.start, problem.goal, world.free_bounds(), validity, params);
  AnytimeRun run;
  run.time_to_first = result.stats.time_to_first_solution;
  run.history = result.stats.cost_history;
  run.simplified_cost = result.stats.final_cost;
  run.iterations = result.stats.iterations;
  return run;
}

void ComparePlanners(const std::vector<PlanningProblem>& problems, int seeds, double seconds,
                     std::ostream& out, ProgressDisplay& progress) {
  const bool ompl = HaveOmpl();
  out << "| map | planner | solved | first solution [ms] | cost @0.2 s [m] | cost @" << seconds
      << " s [m] | simplified [m] | iterations |\n|---|---|---|---|---|---|---|---|\n";
  std::vector<std::string> ratio_rows;
  for (const PlanningProblem& problem : problems) {
    const CollisionWorld world(problem.map, CollisionParams());
    std::vector<AnytimeRun> ours, ompl_default, ompl_informed;
    for (int s = 0; s < seeds; ++s) {
      progress.Show(problem.name + ": run " + std::to_string(s + 1) + "/" + std::to_string(seeds));
      ours.push_back(RunOurs(world, problem, seconds, static_cast<std::uint64_t>(s + 1)));
      if (ompl) {
        ompl_default.push_back(RunOmpl(world, problem, seconds, false));
        ompl_informed.push_back(RunOmpl(world, problem, seconds, true));
      }
    }
    progress.Clear();
    const auto row = [&](const char* planner, const Summary& s) {
      out << "| " << problem.name << " | " << planner << " | " << s.solved << "/" << seeds << " | "
          << Show(s.first_ms, 2) << " | " << Show(s.cost_early, 2) << " | " << Show(s.cost_end, 2)
          << " | " << Show(s.simplified, 2) << " | " << Show(s.iterations, 0) << " |\n";
    };
    const Summary a = Summarize(ours, seconds);
    row("aerobox RRT*", a);
    if (!ompl) continue;
    const Summary b = Summarize(ompl_default, seconds);
    const Summary c = Summarize(ompl_informed, seconds);
    row("OMPL RRTstar", b);
    row("OMPL RRTstar, informed", c);
    for (const auto& [name, ref] : {std::pair{"OMPL RRTstar", b}, std::pair{"OMPL informed", c}}) {
      ratio_rows.push_back(
          "| " + problem.name + " | " + name + " | " + Show(a.first_ms / ref.first_ms, 2) + " | " +
          Show(a.cost_early / ref.cost_early, 3) + " | " + Show(a.cost_end / ref.cost_end, 3) +
          " | " + Show(a.simplified / ref.simplified, 3) + " |");
    }
  }
  if (!ompl) {
    out << "\n(OMPL reference not built: configure with -DAEROBOX_WITH_OMPL=ON)\n";
    return;
  }
  out << "\nRatios ours / OMPL (medians over " << seeds << " seeds; below 1 is better for us)\n\n"
      << "| map | against | first solution | cost @0.2 s | cost @" << seconds
      << " s | simplified |\n|---|---|---|---|---|---|\n";
  for (const std::string& line : ratio_rows) out << line << "\n";
}

}  // namespace aerobox
