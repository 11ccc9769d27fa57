// The build without the OMPL reference (the default for users): the comparison reports only
// aerobox's own numbers.
#include <stdexcept>

#include "bench/planner_comparison.h"

namespace aerobox {

bool HaveOmpl() { return false; }

AnytimeRun RunOmpl(const CollisionWorld&, const PlanningProblem&, double, bool) {
  throw std::logic_error("this build has no OMPL reference (-DAEROBOX_WITH_OMPL=ON)");
}

}  // namespace aerobox
