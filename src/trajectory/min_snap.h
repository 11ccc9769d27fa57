// Minimum-snap trajectories through waypoints (Mellinger and Kumar 2011): minimise the integral
// of squared snap over degree-7 segments with fixed durations, subject to the waypoints, continuity
// of velocity, acceleration, jerk and snap at interior waypoints, rest (v = a = j = 0) at both
// ends (or a given start state) and, optionally, samples of every segment inside an axis-aligned
// box (a safe corridor). A quadratic programme: solved in closed form (equalities only, a sparse
// KKT system) or with Ipopt (with the box constraints; Ipopt stays inside the .cpp).
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "trajectory/polynomial.h"

namespace aerobox {

struct MinSnapProblem {
  std::vector<Vec3> waypoints;    // at least 2 [m]
  std::vector<double> durations;  // one per segment, > 0 [s]
  // Per segment, optional: the box its samples must stay in [m]. Empty vector: no boxes.
  std::vector<std::optional<Aabb>> corridors;
  // Interior samples per segment at which a corridor is enforced (s = k / (n + 1)).
  int samples_per_segment = 16;
  // The first waypoint's velocity [m/s], acceleration [m/s^2] and jerk [m/s^3]: zero starts at
  // rest; a trajectory that continues another starts with that one's (replanning in flight).
  // The last waypoint is always at rest.
  Vec3 start_velocity = Vec3::Zero();
  Vec3 start_acceleration = Vec3::Zero();
  Vec3 start_jerk = Vec3::Zero();

  // Throws std::invalid_argument for inconsistent sizes or non-positive durations.
  void Validate() const;
};

// Thrown by the solves below when the KKT system is singular or its solution not finite
// (degenerate waypoints or durations far outside the numbers' range). GenerateTrajectory turns
// it into a status; it never reaches a user as an exception.
class SingularSystem : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The equality-constrained optimum (corridors ignored), from the KKT system
// [2Q A'; A 0] [c; l] = [0; b] solved with a sparse LU per axis. Throws SingularSystem.
PiecewiseTrajectory SolveMinSnapClosedForm(const MinSnapProblem& problem);

enum class SolveStatus { kSolved, kInfeasible, kFailed };
const char* ToString(SolveStatus status);

struct IpoptSettings {
  double tolerance = 1e-9;   // Ipopt's "tol"
  int max_iterations = 200;  // Ipopt's "max_iter", per solve
  // Ipopt solves while adding violated corridor samples (see SolveMinSnapIpopt), at most.
  int max_constraint_rounds = 10;
  // For fault tests: Ipopt may take no iteration and starts from a point that is not optimal,
  // so it stops with its own failure status (the app sets it from AEROBOX_FAULT=ipopt).
  bool injected_failure = false;
};

struct MinSnapSolution {
  SolveStatus status = SolveStatus::kFailed;
  std::string message;             // Ipopt's return status, in words
  PiecewiseTrajectory trajectory;  // valid when status is kSolved
  int solver_iterations = 0;       // Ipopt's, summed over its solves
};

// The full problem with Ipopt, started from the closed-form solution. Corridor samples enter by
// constraint generation: Ipopt first sees only those the closed form violates, then those its
// own solution violates, until none is; Ipopt runs at least once.
MinSnapSolution SolveMinSnapIpopt(const MinSnapProblem& problem,
                                  const IpoptSettings& settings = {});

}  // namespace aerobox
