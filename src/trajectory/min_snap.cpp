#include "trajectory/min_snap.h"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <IpIpoptApplication.hpp>
#include <IpSolveStatistics.hpp>
#include <IpTNLP.hpp>
#include <cmath>
#include <stdexcept>

namespace aerobox {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;
using Triplets = std::vector<Eigen::Triplet<double>>;

constexpr int kAxes = 3;

// The QP of one axis (the three axes share its structure): variables are the 8 coefficients of
// each segment, segment after segment. Cost x'Qx; equalities A x = b; inequalities l <= G x <= u.
struct AxisQp {
  SparseMatrix cost;        // Q, symmetric
  SparseMatrix equality;    // A
  SparseMatrix inequality;  // G
  Eigen::MatrixXd rhs;      // b, one column per axis
  Eigen::MatrixXd lower;    // l, one column per axis
  Eigen::MatrixXd upper;    // u, one column per axis
};

double FallingFactorial(int k, int r) {
  double f = 1.0;
  for (int i = 0; i < r; ++i) f *= k - i;
  return f;
}

AxisQp BuildQp(const MinSnapProblem& problem) {
  const int segments = static_cast<int>(problem.durations.size());
  const int n = segments * kCoefficients;
  AxisQp qp;

  // cost: per segment T^-7 * integral_0^1 (d^4/ds^4)^2 (see PolynomialSegment::SnapCost)
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
  qp.cost.resize(n, n);
  qp.cost.setFromTriplets(cost.begin(), cost.end());

  // equalities, one row at a time; `targets` holds the right-hand side per axis
  Triplets rows;
  std::vector<Vec3> targets;
  const auto add_row = [&](int segment, const BasisRow& basis, double sign) {
    for (int k = 0; k < kCoefficients; ++k) {
      if (basis[k] != 0.0) {
        rows.emplace_back(static_cast<int>(targets.size()), segment * kCoefficients + k,
                          sign * basis[k]);
      }
    }
  };
  for (int i = 0; i < segments; ++i) {
    const double t = problem.durations[i];
    add_row(i, Basis(0.0, kPosition, t), 1.0);
    targets.push_back(problem.waypoints[i]);
    add_row(i, Basis(1.0, kPosition, t), 1.0);
    targets.push_back(problem.waypoints[i + 1]);
  }
  for (int r = kVelocity; r <= kJerk; ++r) {  // rest at both ends
    add_row(0, Basis(0.0, r, problem.durations.front()), 1.0);
    targets.push_back(Vec3::Zero());
    add_row(segments - 1, Basis(1.0, r, problem.durations.back()), 1.0);
    targets.push_back(Vec3::Zero());
  }
  for (int i = 1; i < segments; ++i) {  // continuity at interior waypoints
    for (int r = kVelocity; r <= kSnap; ++r) {
      add_row(i - 1, Basis(1.0, r, problem.durations[i - 1]), 1.0);
      add_row(i, Basis(0.0, r, problem.durations[i]), -1.0);
      targets.push_back(Vec3::Zero());
    }
  }
  qp.equality.resize(static_cast<int>(targets.size()), n);
  qp.equality.setFromTriplets(rows.begin(), rows.end());
  qp.rhs.resize(static_cast<int>(targets.size()), kAxes);
  for (size_t r = 0; r < targets.size(); ++r) qp.rhs.row(static_cast<int>(r)) = targets[r];

  // inequalities: corridor samples
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
  qp.inequality.resize(m_in, n);
  qp.inequality.setFromTriplets(samples.begin(), samples.end());
  qp.lower.resize(m_in, kAxes);
  qp.upper.resize(m_in, kAxes);
  for (int r = 0; r < m_in; ++r) {
    qp.lower.row(r) = boxes[r].min;
    qp.upper.row(r) = boxes[r].max;
  }
  return qp;
}

PiecewiseTrajectory ToTrajectory(const MinSnapProblem& problem, const Eigen::MatrixXd& x) {
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

// Closed-form coefficients: one column per axis.
Eigen::MatrixXd SolveKkt(const AxisQp& qp) {
  const int n = static_cast<int>(qp.cost.rows());
  const int m = static_cast<int>(qp.equality.rows());
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
    throw std::runtime_error("min-snap KKT system is singular (degenerate waypoints?)");
  }
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n + m, kAxes);
  rhs.bottomRows(m) = qp.rhs;
  const Eigen::MatrixXd solution = lu.solve(rhs);
  return solution.topRows(n);
}

// Ipopt's view: all three axes in one problem (block-diagonal), variables axis after axis.
class MinSnapNlp : public Ipopt::TNLP {
 public:
  MinSnapNlp(const AxisQp& qp, const Eigen::MatrixXd& start) : qp_(qp), start_(start) {
    n_axis_ = static_cast<int>(qp.cost.rows());
    m_eq_ = static_cast<int>(qp.equality.rows());
    m_in_ = static_cast<int>(qp.inequality.rows());
    // the lower triangle of the cost, for the Hessian
    for (int k = 0; k < qp.cost.outerSize(); ++k) {
      for (SparseMatrix::InnerIterator it(qp.cost, k); it; ++it) {
        if (it.row() >= it.col())
          lower_.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
      }
    }
    for (const SparseMatrix* block : {&qp.equality, &qp.inequality}) {
      const int row_offset = block == &qp.equality ? 0 : m_eq_;
      for (int k = 0; k < block->outerSize(); ++k) {
        for (SparseMatrix::InnerIterator it(*block, k); it; ++it) {
          jacobian_.emplace_back(row_offset + static_cast<int>(it.row()),
                                 static_cast<int>(it.col()), it.value());
        }
      }
    }
  }

  bool get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnz_jac_g,
                    Ipopt::Index& nnz_h_lag, IndexStyleEnum& index_style) override {
    n = kAxes * n_axis_;
    m = kAxes * (m_eq_ + m_in_);
    nnz_jac_g = kAxes * static_cast<int>(jacobian_.size());
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
      const int offset = axis * (m_eq_ + m_in_);
      for (int r = 0; r < m_eq_; ++r) g_l[offset + r] = g_u[offset + r] = qp_.rhs(r, axis);
      for (int r = 0; r < m_in_; ++r) {
        g_l[offset + m_eq_ + r] = qp_.lower(r, axis);
        g_u[offset + m_eq_ + r] = qp_.upper(r, axis);
      }
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
      value += c.dot(qp_.cost * c);
    }
    return true;
  }

  bool eval_grad_f(Ipopt::Index, const Ipopt::Number* x, bool, Ipopt::Number* grad) override {
    for (int axis = 0; axis < kAxes; ++axis) {
      const Eigen::Map<const Eigen::VectorXd> c(x + axis * n_axis_, n_axis_);
      Eigen::Map<Eigen::VectorXd>(grad + axis * n_axis_, n_axis_) = 2.0 * (qp_.cost * c);
    }
    return true;
  }

  bool eval_g(Ipopt::Index, const Ipopt::Number* x, bool, Ipopt::Index, Ipopt::Number* g) override {
    for (int axis = 0; axis < kAxes; ++axis) {
      const Eigen::Map<const Eigen::VectorXd> c(x + axis * n_axis_, n_axis_);
      const int offset = axis * (m_eq_ + m_in_);
      Eigen::Map<Eigen::VectorXd>(g + offset, m_eq_) = qp_.equality * c;
      Eigen::Map<Eigen::VectorXd>(g + offset + m_eq_, m_in_) = qp_.inequality * c;
    }
    return true;
  }

  bool eval_jac_g(Ipopt::Index, const Ipopt::Number*, bool, Ipopt::Index, Ipopt::Index,
                  Ipopt::Index* rows, Ipopt::Index* cols, Ipopt::Number* values) override {
    int e = 0;
    for (int axis = 0; axis < kAxes; ++axis) {
      for (const Eigen::Triplet<double>& t : jacobian_) {
        if (values == nullptr) {
          rows[e] = axis * (m_eq_ + m_in_) + t.row();
          cols[e] = axis * n_axis_ + t.col();
        } else {
          values[e] = t.value();
        }
        ++e;
      }
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
  const AxisQp& qp_;
  Eigen::MatrixXd start_;
  int n_axis_ = 0;
  int m_eq_ = 0;
  int m_in_ = 0;
  std::vector<Eigen::Triplet<double>> lower_;
  std::vector<Eigen::Triplet<double>> jacobian_;
  Eigen::MatrixXd solution_;
};

std::string Describe(Ipopt::ApplicationReturnStatus status) {
  switch (status) {
    case Ipopt::Solve_Succeeded:
      return "solved";
    case Ipopt::Solved_To_Acceptable_Level:
      return "solved to acceptable level";
    case Ipopt::Infeasible_Problem_Detected:
      return "infeasible problem detected";
    case Ipopt::Search_Direction_Becomes_Too_Small:
      return "search direction becomes too small";
    case Ipopt::Diverging_Iterates:
      return "diverging iterates";
    case Ipopt::User_Requested_Stop:
      return "user requested stop";
    case Ipopt::Feasible_Point_Found:
      return "feasible point found";
    case Ipopt::Maximum_Iterations_Exceeded:
      return "maximum iterations exceeded";
    case Ipopt::Restoration_Failed:
      return "restoration failed";
    case Ipopt::Error_In_Step_Computation:
      return "error in step computation";
    case Ipopt::Maximum_CpuTime_Exceeded:
      return "maximum CPU time exceeded";
    case Ipopt::Not_Enough_Degrees_Of_Freedom:
      return "not enough degrees of freedom";
    case Ipopt::Invalid_Problem_Definition:
      return "invalid problem definition";
    case Ipopt::Invalid_Option:
      return "invalid option";
    case Ipopt::Invalid_Number_Detected:
      return "invalid number detected";
    case Ipopt::Unrecoverable_Exception:
      return "unrecoverable exception";
    case Ipopt::NonIpopt_Exception_Thrown:
      return "non-Ipopt exception thrown";
    case Ipopt::Insufficient_Memory:
      return "insufficient memory";
    case Ipopt::Internal_Error:
      return "internal error";
  }
  return "unknown Ipopt status " + std::to_string(static_cast<int>(status));
}

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
  problem.Validate();
  return ToTrajectory(problem, SolveKkt(BuildQp(problem)));
}

MinSnapSolution SolveMinSnapIpopt(const MinSnapProblem& problem, const IpoptSettings& settings) {
  problem.Validate();
  const AxisQp qp = BuildQp(problem);
  Ipopt::SmartPtr<MinSnapNlp> nlp = new MinSnapNlp(qp, SolveKkt(qp));
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  // silent, no ipopt.opt read from the working folder, and the QP structure declared
  app->Options()->SetIntegerValue("print_level", 0);
  app->Options()->SetStringValue("sb", "yes");
  app->Options()->SetStringValue("hessian_constant", "yes");
  app->Options()->SetStringValue("jac_c_constant", "yes");
  app->Options()->SetStringValue("jac_d_constant", "yes");
  app->Options()->SetNumericValue("tol", settings.tolerance);
  app->Options()->SetIntegerValue("max_iter", settings.max_iterations);
  MinSnapSolution result;
  if (app->Initialize("") != Ipopt::Solve_Succeeded) {
    result.message = "Ipopt did not initialise";
    return result;
  }
  const Ipopt::ApplicationReturnStatus status = app->OptimizeTNLP(nlp);
  result.message = Describe(status);
  if (Ipopt::SmartPtr<Ipopt::SolveStatistics> stats = app->Statistics(); IsValid(stats)) {
    result.solver_iterations = stats->IterationCount();
  }
  if (status == Ipopt::Solve_Succeeded || status == Ipopt::Solved_To_Acceptable_Level) {
    result.status = SolveStatus::kSolved;
    result.trajectory = ToTrajectory(problem, nlp->solution());
  } else if (status == Ipopt::Infeasible_Problem_Detected) {
    result.status = SolveStatus::kInfeasible;
  }
  return result;
}

}  // namespace aerobox
