#include "trajectory/point_mass.h"

#include <IpIpoptApplication.hpp>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "trajectory/ipopt_status.h"
#include "trajectory/stoppable_tnlp.h"
#include "trajectory/time_allocation.h"

namespace aerobox {
namespace {

constexpr int kAxes = 3;

// The variables, in order: node positions (3 per node), node velocities (3 per node), the
// constant acceleration of each interval (3 per interval), each segment's duration. Node
// i * n is waypoint i; an interval of segment i lasts T_i / n. Constraints, in order: per
// interval, the exact integration of its constant acceleration (3 rows for the position, 3 for
// the velocity); per interval |a|^2 <= A^2; per node |v|^2 <= V^2 (the velocity is linear over
// an interval, so the ball holds in between too).
class PointMassNlp : public StoppableTnlp {
 public:
  PointMassNlp(const std::vector<Vec3>& waypoints, const PointMassParams& params)
      : waypoints_(waypoints),
        params_(params),
        segments_(static_cast<int>(waypoints.size()) - 1),
        n_(params.intervals),
        intervals_(segments_ * n_),
        nodes_(intervals_ + 1) {}

  int P(int node, int axis) const { return kAxes * node + axis; }
  int V(int node, int axis) const { return kAxes * (nodes_ + node) + axis; }
  int A(int interval, int axis) const { return kAxes * (2 * nodes_ + interval) + axis; }
  int T(int segment) const { return kAxes * (2 * nodes_ + intervals_) + segment; }
  int Variables() const { return T(segments_); }
  int Segment(int interval) const { return interval / n_; }

  const std::vector<double>& solution() const { return solution_; }

  bool get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnz_jac_g,
                    Ipopt::Index& nnz_h_lag, IndexStyleEnum& index_style) override {
    n = Variables();
    m = 2 * kAxes * intervals_ + intervals_ + nodes_;
    // position rows: p+, p, v, a, T; velocity rows: v+, v, a, T; norms: 3 each
    nnz_jac_g = kAxes * intervals_ * (5 + 4) + kAxes * (intervals_ + nodes_);
    // per interval: (T, v) and (T, a) per axis; diagonals of a and v; (T, T) per segment
    nnz_h_lag = 2 * kAxes * intervals_ + kAxes * (intervals_ + nodes_) + segments_;
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Ipopt::Index n, Ipopt::Number* x_l, Ipopt::Number* x_u, Ipopt::Index m,
                       Ipopt::Number* g_l, Ipopt::Number* g_u) override {
    constexpr double kFree = 2e19;  // Ipopt's infinity
    std::fill(x_l, x_l + n, -kFree);
    std::fill(x_u, x_u + n, kFree);
    for (int i = 0; i <= segments_; ++i) {
      for (int k = 0; k < kAxes; ++k) x_l[P(i * n_, k)] = x_u[P(i * n_, k)] = waypoints_[i][k];
    }
    for (int k = 0; k < kAxes; ++k) {
      x_l[V(0, k)] = x_u[V(0, k)] = 0.0;
      x_l[V(nodes_ - 1, k)] = x_u[V(nodes_ - 1, k)] = 0.0;
    }
    for (int i = 0; i < segments_; ++i) x_l[T(i)] = 1e-3;
    const int dynamics = 2 * kAxes * intervals_;
    std::fill(g_l, g_l + dynamics, 0.0);
    std::fill(g_u, g_u + dynamics, 0.0);
    const double a2 = params_.max_accel * params_.max_accel;
    const double v2 = params_.max_speed * params_.max_speed;
    for (int r = dynamics; r < m; ++r) {
      g_l[r] = -kFree;
      g_u[r] = r < dynamics + intervals_ ? a2 : v2;
    }
    return true;
  }

  // Stopping at every waypoint: a rest-to-rest trapezoid along each straight segment, with the
  // acceleration of each interval the mean over it.
  bool get_starting_point(Ipopt::Index, bool, Ipopt::Number* x, bool, Ipopt::Number*,
                          Ipopt::Number*, Ipopt::Index, bool, Ipopt::Number*) override {
    const double vmax = params_.max_speed;
    const double amax = params_.max_accel;
    for (int i = 0; i < segments_; ++i) {
      const Vec3 d = waypoints_[i + 1] - waypoints_[i];
      const double length = d.norm();
      const double duration = TrapezoidTime(length, vmax, amax);
      const double peak = std::min(vmax, std::sqrt(amax * length));
      const double ramp = peak / amax;  // [s]
      const auto speed = [&](double t) {
        return std::min({peak, amax * t, amax * (duration - t)});
      };
      const auto distance = [&](double t) {
        if (t <= ramp) return 0.5 * amax * t * t;
        if (t <= duration - ramp) return 0.5 * peak * ramp + peak * (t - ramp);
        const double left = duration - t;
        return length - 0.5 * amax * left * left;
      };
      x[T(i)] = duration;
      const double h = duration / n_;
      for (int j = 0; j <= n_; ++j) {
        const int node = i * n_ + j;
        const double t = j * h;
        for (int k = 0; k < kAxes; ++k) {
          x[P(node, k)] = waypoints_[i][k] + d[k] / length * std::clamp(distance(t), 0.0, length);
          x[V(node, k)] = d[k] / length * std::max(0.0, speed(t));
        }
        if (j == n_) continue;
        const double mean = (std::max(0.0, speed(t + h)) - std::max(0.0, speed(t))) / h;
        for (int k = 0; k < kAxes; ++k) x[A(node, k)] = d[k] / length * mean;
      }
    }
    return true;
  }

  bool eval_f(Ipopt::Index, const Ipopt::Number* x, bool, Ipopt::Number& value) override {
    value = 0.0;
    for (int i = 0; i < segments_; ++i) value += x[T(i)];
    return true;
  }

  bool eval_grad_f(Ipopt::Index n, const Ipopt::Number*, bool, Ipopt::Number* grad) override {
    std::fill(grad, grad + n, 0.0);
    for (int i = 0; i < segments_; ++i) grad[T(i)] = 1.0;
    return true;
  }

  bool eval_g(Ipopt::Index, const Ipopt::Number* x, bool, Ipopt::Index, Ipopt::Number* g) override {
    int r = 0;
    for (int j = 0; j < intervals_; ++j) {
      const double h = x[T(Segment(j))] / n_;
      for (int k = 0; k < kAxes; ++k) {
        g[r++] = x[P(j + 1, k)] - x[P(j, k)] - x[V(j, k)] * h - 0.5 * x[A(j, k)] * h * h;
        g[r++] = x[V(j + 1, k)] - x[V(j, k)] - x[A(j, k)] * h;
      }
    }
    for (int j = 0; j < intervals_; ++j) {
      g[r++] = x[A(j, 0)] * x[A(j, 0)] + x[A(j, 1)] * x[A(j, 1)] + x[A(j, 2)] * x[A(j, 2)];
    }
    for (int j = 0; j < nodes_; ++j) {
      g[r++] = x[V(j, 0)] * x[V(j, 0)] + x[V(j, 1)] * x[V(j, 1)] + x[V(j, 2)] * x[V(j, 2)];
    }
    return true;
  }

  bool eval_jac_g(Ipopt::Index, const Ipopt::Number* x, bool, Ipopt::Index, Ipopt::Index,
                  Ipopt::Index* rows, Ipopt::Index* cols, Ipopt::Number* values) override {
    int e = 0;
    const auto put = [&](int row, int col, double value) {
      if (values == nullptr) {
        rows[e] = row;
        cols[e] = col;
      } else {
        values[e] = value;
      }
      ++e;
    };
    int r = 0;
    for (int j = 0; j < intervals_; ++j) {
      const int s = Segment(j);
      const double tau = x == nullptr ? 0.0 : x[T(s)];
      const double h = tau / n_;
      for (int k = 0; k < kAxes; ++k) {
        const double v = x == nullptr ? 0.0 : x[V(j, k)];
        const double a = x == nullptr ? 0.0 : x[A(j, k)];
        put(r, P(j + 1, k), 1.0);
        put(r, P(j, k), -1.0);
        put(r, V(j, k), -h);
        put(r, A(j, k), -0.5 * h * h);
        put(r, T(s), -v / n_ - a * tau / (n_ * n_));
        ++r;
        put(r, V(j + 1, k), 1.0);
        put(r, V(j, k), -1.0);
        put(r, A(j, k), -h);
        put(r, T(s), -a / n_);
        ++r;
      }
    }
    for (int j = 0; j < intervals_; ++j, ++r) {
      for (int k = 0; k < kAxes; ++k) put(r, A(j, k), x == nullptr ? 0.0 : 2.0 * x[A(j, k)]);
    }
    for (int j = 0; j < nodes_; ++j, ++r) {
      for (int k = 0; k < kAxes; ++k) put(r, V(j, k), x == nullptr ? 0.0 : 2.0 * x[V(j, k)]);
    }
    return true;
  }

  // The objective is linear; the Hessian is the constraints' alone. Lower triangle: every T
  // comes after the nodes' and intervals' variables.
  bool eval_h(Ipopt::Index, const Ipopt::Number* x, bool, Ipopt::Number, Ipopt::Index,
              const Ipopt::Number* lambda, bool, Ipopt::Index, Ipopt::Index* rows,
              Ipopt::Index* cols, Ipopt::Number* values) override {
    const bool structure = values == nullptr;
    int e = 0;
    const auto put = [&](int row, int col, double value) {
      if (structure) {
        rows[e] = row;
        cols[e] = col;
      } else {
        values[e] = value;
      }
      ++e;
    };
    std::vector<double> tt(segments_, 0.0);  // d2 / dT2, summed per segment
    for (int j = 0; j < intervals_; ++j) {
      const int s = Segment(j);
      const double tau = structure ? 0.0 : x[T(s)];
      for (int k = 0; k < kAxes; ++k) {
        const double lp = structure ? 0.0 : lambda[2 * (kAxes * j + k)];      // position row
        const double lv = structure ? 0.0 : lambda[2 * (kAxes * j + k) + 1];  // velocity row
        put(T(s), V(j, k), -lp / n_);
        put(T(s), A(j, k), -lp * tau / (n_ * n_) - lv / n_);
        if (!structure) tt[s] += -lp * x[A(j, k)] / (n_ * n_);
      }
    }
    const int norms = 2 * kAxes * intervals_;
    for (int j = 0; j < intervals_; ++j) {
      const double mu = structure ? 0.0 : lambda[norms + j];
      for (int k = 0; k < kAxes; ++k) put(A(j, k), A(j, k), 2.0 * mu);
    }
    for (int j = 0; j < nodes_; ++j) {
      const double mu = structure ? 0.0 : lambda[norms + intervals_ + j];
      for (int k = 0; k < kAxes; ++k) put(V(j, k), V(j, k), 2.0 * mu);
    }
    for (int s = 0; s < segments_; ++s) put(T(s), T(s), tt[s]);
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn, Ipopt::Index n, const Ipopt::Number* x,
                         const Ipopt::Number*, const Ipopt::Number*, Ipopt::Index,
                         const Ipopt::Number*, const Ipopt::Number*, Ipopt::Number,
                         const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    solution_.assign(x, x + n);
  }

 private:
  const std::vector<Vec3>& waypoints_;
  PointMassParams params_;
  int segments_;
  int n_;
  int intervals_;
  int nodes_;
  std::vector<double> solution_;
};

void Validate(const std::vector<Vec3>& waypoints, const PointMassParams& params) {
  if (waypoints.size() < 2) throw std::invalid_argument("point mass: fewer than 2 waypoints");
  for (size_t i = 0; i < waypoints.size(); ++i) {
    if (!waypoints[i].allFinite()) throw std::invalid_argument("point mass: non-finite waypoint");
    if (i > 0 && (waypoints[i] - waypoints[i - 1]).norm() < 1e-9) {
      throw std::invalid_argument("point mass: waypoint " + std::to_string(i) +
                                  " repeats the one before");
    }
  }
  if (!(params.max_speed > 0 && std::isfinite(params.max_speed)) ||
      !(params.max_accel > 0 && std::isfinite(params.max_accel))) {
    throw std::invalid_argument("point mass: limits must be positive and finite");
  }
  if (params.intervals < 2) throw std::invalid_argument("point mass: intervals < 2");
  if (params.max_iterations < 1) throw std::invalid_argument("point mass: max_iterations < 1");
}

}  // namespace

PointMassResult MinimumTimePointMass(const std::vector<Vec3>& waypoints,
                                     const PointMassParams& params) {
  Validate(waypoints, params);
  PointMassResult result;
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  app->Options()->SetIntegerValue("print_level", 0);
  app->Options()->SetStringValue("sb", "yes");
  app->Options()->SetIntegerValue("max_iter", params.max_iterations);
  app->Options()->SetNumericValue("tol", 1e-8);
  if (app->Initialize("") != Ipopt::Solve_Succeeded) {
    result.message = "Ipopt did not initialise";
    return result;
  }
  Ipopt::SmartPtr<PointMassNlp> nlp = new PointMassNlp(waypoints, params);
  const Ipopt::ApplicationReturnStatus status = app->OptimizeTNLP(nlp);
  ThrowIfStoppedOnRequest(status, "allocating segment times (Ipopt, point mass)");
  result.message = DescribeIpoptStatus(status);
  result.solved = status == Ipopt::Solve_Succeeded || status == Ipopt::Solved_To_Acceptable_Level;
  if (!result.solved) return result;
  const std::vector<double>& x = nlp->solution();
  const int segments = static_cast<int>(waypoints.size()) - 1;
  for (int i = 0; i < segments; ++i) {
    result.segment_times.push_back(x[nlp->T(i)]);
    result.time += x[nlp->T(i)];
  }
  for (int i = 0; i <= segments; ++i) {
    const int node = i * params.intervals;
    result.waypoint_velocity.emplace_back(x[nlp->V(node, 0)], x[nlp->V(node, 1)],
                                          x[nlp->V(node, 2)]);
  }
  return result;
}

}  // namespace aerobox
