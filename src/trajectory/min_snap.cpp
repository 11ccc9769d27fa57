#include "trajectory/min_snap.h"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <IpIpoptApplication.hpp>
#include <IpSolveStatistics.hpp>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "trajectory/ipopt_status.h"
#include "trajectory/stoppable_tnlp.h"

namespace aerobox {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;
using Triplets = std::vector<Eigen::Triplet<double>>;

constexpr int kAxes = 3;

// The QP of one axis (the three axes share its structure except for right-hand sides).
//
// The unknowns are not the 8 coefficients of each segment but the derivatives at the waypoints
// that are still free: velocity, acceleration and jerk at each interior waypoint (Richter, Bry
// and Roy 2013). A segment's coefficients follow linearly from the position, velocity,
// acceleration and jerk at its two ends, so the waypoint positions, rest at both ends and
// continuity of velocity, acceleration and jerk hold by construction; continuity of snap stays
// an equality. The same QP as over the coefficients, in fewer variables, which keeps Ipopt's
// linear systems small. coefficients = P z + q; cost z'Hz + f'z (+ constant); equalities
// A z = b; inequalities l <= G z <= u.
struct AxisQp {
  SparseMatrix cost;             // H, symmetric
  Eigen::MatrixXd linear;        // f, one column per axis
  SparseMatrix equality;         // A
  SparseMatrix inequality;       // G
  Eigen::MatrixXd rhs;           // b, one column per axis
  Eigen::MatrixXd lower;         // l, one column per axis
  Eigen::MatrixXd upper;         // u, one column per axis
  SparseMatrix to_coefficients;  // P
  Eigen::MatrixXd offset;        // q, one column per axis
};

double FallingFactorial(int k, int r) {
  double f = 1.0;
  for (int i = 0; i < r; ++i) f *= k - i;
  return f;
}

// Index of the free derivative of order r (1..3) at interior waypoint j (1..M-1).
int FreeIndex(int j, int r) { return (j - 1) * kJerk + (r - 1); }

AxisQp BuildQp(const MinSnapProblem& problem) {
  const int segments = static_cast<int>(problem.durations.size());
  const int n = segments * kCoefficients;
  const int free = kJerk * (segments - 1);

  // P and q: each segment's coefficients from the derivatives at its ends, c = B^-1 d, where
  // B stacks the derivatives 0..3 at s = 0 and at s = 1
  Triplets to_coefficients;
  Eigen::MatrixXd offset = Eigen::MatrixXd::Zero(n, kAxes);
  for (int i = 0; i < segments; ++i) {
    const double t = problem.durations[i];
    Eigen::Matrix<double, kCoefficients, kCoefficients> ends;
    for (int r = 0; r <= kJerk; ++r) {
      ends.row(r) = Basis(0.0, r, t);
      ends.row(kJerk + 1 + r) = Basis(1.0, r, t);
    }
    const Eigen::Matrix<double, kCoefficients, kCoefficients> inverse = ends.inverse();
    for (int e = 0; e < kCoefficients; ++e) {
      const int knot = i + e / (kJerk + 1);
      const int r = e % (kJerk + 1);
      for (int row = 0; row < kCoefficients; ++row) {
        const double h = inverse(row, e);
        if (h == 0.0) continue;
        if (r == kPosition) {
          offset.row(i * kCoefficients + row) += h * problem.waypoints[knot].transpose();
        } else if (knot == 0) {  // the start's derivatives are given (zero: at rest)
          const Vec3& d = r == kVelocity       ? problem.start_velocity
                          : r == kAcceleration ? problem.start_acceleration
                                               : problem.start_jerk;
          offset.row(i * kCoefficients + row) += h * d.transpose();
        } else if (knot != segments) {  // at rest at the end: zero, not free
          to_coefficients.emplace_back(i * kCoefficients + row, FreeIndex(knot, r), h);
        }
      }
    }
  }
  AxisQp qp;
  qp.to_coefficients.resize(n, free);
  qp.to_coefficients.setFromTriplets(to_coefficients.begin(), to_coefficients.end());
  qp.offset = offset;
  const SparseMatrix& p = qp.to_coefficients;

  // the snap cost over the coefficients: per segment T^-7 integral_0^1 (d^4/ds^4)^2
  Triplets cost;
  for (int i = 0; i < segments; ++i) {
    const double scale = std::pow(problem.durations[i], -7);
    for (int j = kSnap; j < kCoefficients; ++j) {
      for (int k = kSnap; k < kCoefficients; ++k) {
        const double q = FallingFactorial(j, kSnap) * FallingFactorial(k, kSnap) / (j + k - 7);
        cost.emplace_back(i * kCoefficients + j, i * kCoefficients + k, scale * q);
      }
    }
  }
  SparseMatrix coefficient_cost(n, n);
  coefficient_cost.setFromTriplets(cost.begin(), cost.end());
  qp.cost = SparseMatrix(p.transpose() * coefficient_cost * p);
  qp.linear = 2.0 * (p.transpose() * (coefficient_cost * offset));

  // continuity of snap at interior waypoints
  Triplets snap;
  for (int j = 1; j < segments; ++j) {
    const BasisRow end = Basis(1.0, kSnap, problem.durations[j - 1]);
    const BasisRow start = Basis(0.0, kSnap, problem.durations[j]);
    for (int k = 0; k < kCoefficients; ++k) {
      snap.emplace_back(j - 1, (j - 1) * kCoefficients + k, end[k]);
      snap.emplace_back(j - 1, j * kCoefficients + k, -start[k]);
    }
  }
  SparseMatrix continuity(segments - 1, n);
  continuity.setFromTriplets(snap.begin(), snap.end());
  qp.equality = SparseMatrix(continuity * p);
  qp.rhs = -(continuity * offset);

  // corridor samples
  Triplets samples;
  std::vector<Aabb> boxes;
  for (int i = 0; i < segments && !problem.corridors.empty(); ++i) {
    if (!problem.corridors[i]) continue;
    for (int k = 1; k <= problem.samples_per_segment; ++k) {
      const BasisRow basis = Basis(static_cast<double>(k) / (problem.samples_per_segment + 1),
                                   kPosition, problem.durations[i]);
      for (int c = 0; c < kCoefficients; ++c) {
        samples.emplace_back(static_cast<int>(boxes.size()), i * kCoefficients + c, basis[c]);
      }
      boxes.push_back(*problem.corridors[i]);
    }
  }
  const int m_in = static_cast<int>(boxes.size());
  SparseMatrix sample_rows(m_in, n);
  sample_rows.setFromTriplets(samples.begin(), samples.end());
  qp.inequality = SparseMatrix(sample_rows * p);
  const Eigen::MatrixXd fixed_part = sample_rows * offset;
  qp.lower.resize(m_in, kAxes);
  qp.upper.resize(m_in, kAxes);
  for (int r = 0; r < m_in; ++r) {
    qp.lower.row(r) = boxes[r].min.transpose() - fixed_part.row(r);
    qp.upper.row(r) = boxes[r].max.transpose() - fixed_part.row(r);
  }
  return qp;
}

PiecewiseTrajectory ToTrajectory(const MinSnapProblem& problem, const AxisQp& qp,
                                 const Eigen::MatrixXd& z) {
  const Eigen::MatrixXd x = qp.to_coefficients * z + qp.offset;
  std::vector<PolynomialSegment> segments;
  for (size_t i = 0; i < problem.durations.size(); ++i) {
    Eigen::MatrixXd coefficients(kAxes, kCoefficients);
    for (int axis = 0; axis < kAxes; ++axis) {
      coefficients.row(axis) =
          x.col(axis).segment(static_cast<int>(i) * kCoefficients, kCoefficients).transpose();
    }
    segments.emplace_back(coefficients, problem.durations[i]);
  }
  return PiecewiseTrajectory(std::move(segments));
}

// Closed-form free derivatives, one column per axis: the KKT system
// [2H A'; A 0] [z; l] = [-f; b] with a sparse LU.
Eigen::MatrixXd SolveKkt(const AxisQp& qp) {
  const int n = static_cast<int>(qp.cost.rows());
  const int m = static_cast<int>(qp.equality.rows());
  if (n == 0) return Eigen::MatrixXd::Zero(0, kAxes);
  Triplets kkt;
  for (int k = 0; k < qp.cost.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(qp.cost, k); it; ++it) {
      kkt.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), 2.0 * it.value());
    }
  }
  for (int k = 0; k < qp.equality.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(qp.equality, k); it; ++it) {
      kkt.emplace_back(n + static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
      kkt.emplace_back(static_cast<int>(it.col()), n + static_cast<int>(it.row()), it.value());
    }
  }
  SparseMatrix system(n + m, n + m);
  system.setFromTriplets(kkt.begin(), kkt.end());
  Eigen::SparseLU<SparseMatrix> lu;
  lu.compute(system);
  if (lu.info() != Eigen::Success) {
    throw SingularSystem("the minimum-snap system is singular (degenerate waypoints or times)");
  }
  Eigen::MatrixXd rhs(n + m, kAxes);
  rhs.topRows(n) = -qp.linear;
  rhs.bottomRows(m) = qp.rhs;
  const Eigen::MatrixXd solution = lu.solve(rhs);
  if (lu.info() != Eigen::Success || !solution.allFinite()) {
    throw SingularSystem("the minimum-snap system has no finite solution (degenerate times)");
  }
  return solution.topRows(n);
}

// One corridor sample of one axis: a row of G and the axis it bounds.
struct ActiveRow {
  int axis;
  int row;
  bool operator==(const ActiveRow& other) const { return axis == other.axis && row == other.row; }
};

// Ipopt's view: all three axes in one problem (block-diagonal), variables axis after axis; the
// equalities of every axis, then the selected corridor rows.
class MinSnapNlp : public StoppableTnlp {
 public:
  MinSnapNlp(const AxisQp& qp, const Eigen::MatrixXd& start, std::vector<ActiveRow> active)
      : qp_(qp), start_(start), active_(std::move(active)) {
    n_axis_ = static_cast<int>(qp.cost.rows());
    m_eq_ = static_cast<int>(qp.equality.rows());
    m_in_ = static_cast<int>(active_.size());
    inequality_rows_ = qp.inequality;  // row-major copy for row access

    // the lower triangle of the cost, for the Hessian
    for (int k = 0; k < qp.cost.outerSize(); ++k) {
      for (SparseMatrix::InnerIterator it(qp.cost, k); it; ++it) {
        if (it.row() >= it.col())
          lower_.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
      }
    }
    for (int axis = 0; axis < kAxes; ++axis) {
      for (int k = 0; k < qp.equality.outerSize(); ++k) {
        for (SparseMatrix::InnerIterator it(qp.equality, k); it; ++it) {
          jacobian_.emplace_back(axis * m_eq_ + static_cast<int>(it.row()),
                                 axis * n_axis_ + static_cast<int>(it.col()), it.value());
        }
      }
    }
    for (int r = 0; r < m_in_; ++r) {
      for (RowMajor::InnerIterator it(inequality_rows_, active_[r].row); it; ++it) {
        jacobian_.emplace_back(kAxes * m_eq_ + r,
                               active_[r].axis * n_axis_ + static_cast<int>(it.col()), it.value());
      }
    }
  }

  bool get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnz_jac_g,
                    Ipopt::Index& nnz_h_lag, IndexStyleEnum& index_style) override {
    n = kAxes * n_axis_;
    m = kAxes * m_eq_ + m_in_;
    nnz_jac_g = static_cast<int>(jacobian_.size());
    nnz_h_lag = kAxes * static_cast<int>(lower_.size());
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Ipopt::Index n, Ipopt::Number* x_l, Ipopt::Number* x_u, Ipopt::Index,
                       Ipopt::Number* g_l, Ipopt::Number* g_u) override {
    for (int i = 0; i < n; ++i) {
      x_l[i] = -1e20;
      x_u[i] = 1e20;
    }
    for (int axis = 0; axis < kAxes; ++axis) {
      for (int r = 0; r < m_eq_; ++r)
        g_l[axis * m_eq_ + r] = g_u[axis * m_eq_ + r] = qp_.rhs(r, axis);
    }
    for (int r = 0; r < m_in_; ++r) {
      g_l[kAxes * m_eq_ + r] = qp_.lower(active_[r].row, active_[r].axis);
      g_u[kAxes * m_eq_ + r] = qp_.upper(active_[r].row, active_[r].axis);
    }
    return true;
  }

  bool get_starting_point(Ipopt::Index, bool, Ipopt::Number* x, bool, Ipopt::Number*,
                          Ipopt::Number*, Ipopt::Index, bool, Ipopt::Number*) override {
    for (int axis = 0; axis < kAxes; ++axis) {
      for (int i = 0; i < n_axis_; ++i) x[axis * n_axis_ + i] = start_(i, axis);
    }
    return true;
  }

  bool eval_f(Ipopt::Index, const Ipopt::Number* x, bool, Ipopt::Number& value) override {
    value = 0.0;
    for (int axis = 0; axis < kAxes; ++axis) {
      const Eigen::Map<const Eigen::VectorXd> c(x + axis * n_axis_, n_axis_);
      value += c.dot(qp_.cost * c) + qp_.linear.col(axis).dot(c);
    }
    return true;
  }

  bool eval_grad_f(Ipopt::Index, const Ipopt::Number* x, bool, Ipopt::Number* grad) override {
    for (int axis = 0; axis < kAxes; ++axis) {
      const Eigen::Map<const Eigen::VectorXd> c(x + axis * n_axis_, n_axis_);
      Eigen::Map<Eigen::VectorXd>(grad + axis * n_axis_, n_axis_) =
          2.0 * (qp_.cost * c) + qp_.linear.col(axis);
    }
    return true;
  }

  bool eval_g(Ipopt::Index, const Ipopt::Number* x, bool, Ipopt::Index, Ipopt::Number* g) override {
    for (int axis = 0; axis < kAxes; ++axis) {
      const Eigen::Map<const Eigen::VectorXd> c(x + axis * n_axis_, n_axis_);
      Eigen::Map<Eigen::VectorXd>(g + axis * m_eq_, m_eq_) = qp_.equality * c;
    }
    for (int r = 0; r < m_in_; ++r) {
      const Eigen::Map<const Eigen::VectorXd> c(x + active_[r].axis * n_axis_, n_axis_);
      g[kAxes * m_eq_ + r] = inequality_rows_.row(active_[r].row).dot(c);
    }
    return true;
  }

  bool eval_jac_g(Ipopt::Index, const Ipopt::Number*, bool, Ipopt::Index, Ipopt::Index,
                  Ipopt::Index* rows, Ipopt::Index* cols, Ipopt::Number* values) override {
    int e = 0;
    for (const Eigen::Triplet<double>& t : jacobian_) {
      if (values == nullptr) {
        rows[e] = t.row();
        cols[e] = t.col();
      } else {
        values[e] = t.value();
      }
      ++e;
    }
    return true;
  }

  bool eval_h(Ipopt::Index, const Ipopt::Number*, bool, Ipopt::Number obj_factor, Ipopt::Index,
              const Ipopt::Number*, bool, Ipopt::Index, Ipopt::Index* rows, Ipopt::Index* cols,
              Ipopt::Number* values) override {
    int e = 0;
    for (int axis = 0; axis < kAxes; ++axis) {
      for (const Eigen::Triplet<double>& t : lower_) {
        if (values == nullptr) {
          rows[e] = axis * n_axis_ + t.row();
          cols[e] = axis * n_axis_ + t.col();
        } else {
          values[e] = 2.0 * obj_factor * t.value();  // the constraints are linear
        }
        ++e;
      }
    }
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn, Ipopt::Index, const Ipopt::Number* x,
                         const Ipopt::Number*, const Ipopt::Number*, Ipopt::Index,
                         const Ipopt::Number*, const Ipopt::Number*, Ipopt::Number,
                         const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    solution_.resize(n_axis_, kAxes);
    for (int axis = 0; axis < kAxes; ++axis) {
      for (int i = 0; i < n_axis_; ++i) solution_(i, axis) = x[axis * n_axis_ + i];
    }
  }

  const Eigen::MatrixXd& solution() const { return solution_; }

 private:
  using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;
  const AxisQp& qp_;
  Eigen::MatrixXd start_;
  std::vector<ActiveRow> active_;
  RowMajor inequality_rows_;
  int n_axis_ = 0;
  int m_eq_ = 0;
  int m_in_ = 0;
  std::vector<Eigen::Triplet<double>> lower_;
  std::vector<Eigen::Triplet<double>> jacobian_;
  Eigen::MatrixXd solution_;
};

}  // namespace

void MinSnapProblem::Validate() const {
  if (waypoints.size() < 2) throw std::invalid_argument("MinSnapProblem: fewer than 2 waypoints");
  if (durations.size() + 1 != waypoints.size()) {
    throw std::invalid_argument("MinSnapProblem: need one duration per segment");
  }
  for (const double t : durations) {
    if (!(t > 0 && std::isfinite(t))) throw std::invalid_argument("MinSnapProblem: duration <= 0");
  }
  for (const Vec3& w : waypoints) {
    if (!w.allFinite()) throw std::invalid_argument("MinSnapProblem: non-finite waypoint");
  }
  if (!start_velocity.allFinite() || !start_acceleration.allFinite() || !start_jerk.allFinite()) {
    throw std::invalid_argument("MinSnapProblem: non-finite start state");
  }
  if (!corridors.empty() && corridors.size() != durations.size()) {
    throw std::invalid_argument("MinSnapProblem: need one corridor entry per segment");
  }
  if (samples_per_segment < 1)
    throw std::invalid_argument("MinSnapProblem: samples_per_segment < 1");
}

const char* ToString(SolveStatus status) {
  switch (status) {
    case SolveStatus::kSolved:
      return "solved";
    case SolveStatus::kInfeasible:
      return "infeasible";
    case SolveStatus::kFailed:
      return "failed";
  }
  return "?";
}

PiecewiseTrajectory SolveMinSnapClosedForm(const MinSnapProblem& problem) {
  // the time searches call this hundreds of times: each call is a point to stop at
  ThrowIfStopRequested("solving the trajectory (minimum snap, closed form)");
  problem.Validate();
  const AxisQp qp = BuildQp(problem);
  return ToTrajectory(problem, qp, SolveKkt(qp));
}

MinSnapSolution SolveMinSnapIpopt(const MinSnapProblem& problem, const IpoptSettings& settings) {
  problem.Validate();
  const AxisQp qp = BuildQp(problem);
  // one application per thread, configured once: creating and initialising one costs about as
  // much as solving a 20-segment problem
  thread_local Ipopt::SmartPtr<Ipopt::IpoptApplication> app;
  thread_local bool ready = false;
  MinSnapSolution result;
  if (!ready) {
    app = IpoptApplicationFactory();
    // silent, no ipopt.opt read from the working folder, and the QP structure declared
    app->Options()->SetIntegerValue("print_level", 0);
    app->Options()->SetStringValue("sb", "yes");
    app->Options()->SetStringValue("hessian_constant", "yes");
    app->Options()->SetStringValue("jac_c_constant", "yes");
    app->Options()->SetStringValue("jac_d_constant", "yes");
    if (app->Initialize("") != Ipopt::Solve_Succeeded) {
      result.message = "Ipopt did not initialise";
      return result;
    }
    ready = true;
  }
  const bool fail = settings.injected_failure;
  app->Options()->SetNumericValue("tol", settings.tolerance);
  app->Options()->SetIntegerValue("max_iter", fail ? 0 : settings.max_iterations);

  // constraint generation: solve with the corridor samples that the current solution
  // violates, add the ones the new solution violates, repeat. Each problem relaxes the full
  // one, so a solution that meets every sample is the full problem's optimum; usually a few
  // of the samples are active, and Ipopt's systems stay small.
  Eigen::MatrixXd x;
  try {
    x = SolveKkt(qp);
  } catch (const SingularSystem& e) {
    result.message = e.what();
    return result;
  }
  if (x.rows() == 0) {
    // a single segment is fully determined by its ends: nothing for Ipopt to choose
    const bool inside = ((qp.lower.array() <= 0.0).all() && (qp.upper.array() >= 0.0).all());
    result.status = inside ? SolveStatus::kSolved : SolveStatus::kInfeasible;
    result.message = "one segment: determined by its ends";
    if (inside) result.trajectory = ToTrajectory(problem, qp, x);
    return result;
  }
  std::vector<ActiveRow> active;
  const double slack = 1e-7;  // [m] below Ipopt's tolerance: a sample this close is met
  for (int round = 0; round < settings.max_constraint_rounds; ++round) {
    bool added = false;
    for (int axis = 0; axis < kAxes; ++axis) {
      const Eigen::VectorXd g = qp.inequality * x.col(axis);
      for (int r = 0; r < g.size(); ++r) {
        if (g[r] >= qp.lower(r, axis) - slack && g[r] <= qp.upper(r, axis) + slack) continue;
        // a violated sample brings in every sample of its segment on this axis: the curve
        // leaves the corridor over a stretch, and one round then usually settles it
        const int first = r - r % problem.samples_per_segment;
        for (int k = first; k < first + problem.samples_per_segment; ++k) {
          const ActiveRow row{axis, k};
          if (std::find(active.begin(), active.end(), row) == active.end()) {
            active.push_back(row);
            added = true;
          }
        }
      }
    }
    if (round > 0 && !added) {
      result.status = SolveStatus::kSolved;
      result.trajectory = ToTrajectory(problem, qp, x);
      return result;
    }
    if (fail) x.setZero();
    Ipopt::SmartPtr<MinSnapNlp> nlp = new MinSnapNlp(qp, x, active);
    const Ipopt::ApplicationReturnStatus status = app->OptimizeTNLP(nlp);
    ThrowIfStoppedOnRequest(status, "solving the trajectory (Ipopt, minimum snap)");
    result.message = DescribeIpoptStatus(status);
    if (Ipopt::SmartPtr<Ipopt::SolveStatistics> stats = app->Statistics(); IsValid(stats)) {
      result.solver_iterations += stats->IterationCount();
    }
    if (status == Ipopt::Infeasible_Problem_Detected) {
      result.status = SolveStatus::kInfeasible;
      return result;
    }
    if (status != Ipopt::Solve_Succeeded && status != Ipopt::Solved_To_Acceptable_Level) {
      return result;
    }
    x = nlp->solution();
  }
  result.message = "corridor samples still violated after " +
                   std::to_string(settings.max_constraint_rounds) + " rounds";
  return result;
}

}  // namespace aerobox
