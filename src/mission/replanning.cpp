#include "mission/replanning.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>

#include "common/number_format.h"
#include "common/seed.h"
#include "planning/path_simplify.h"
#include "planning/rrt_star.h"

namespace aerobox {
namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

// The reference `current` until `t_switch`, then `next` (which starts in current's state there).
Reference Splice(const Reference& current, double t_switch, const PiecewiseTrajectory& next) {
  Reference r;
  r.duration = t_switch + next.duration();
  r.heading = current.heading;
  r.evaluate = [current, t_switch, next](double t, int derivative) -> Vec3 {
    if (t < t_switch) return current.evaluate(t, derivative);
    return next.Evaluate3(std::min(t - t_switch, next.duration()), derivative);
  };
  return r;
}

TrajectoryWorld ViewOf(const CollisionWorld& world) {
  return {[&world](const Aabb& box) { return world.IsBoxFree(box); },
          [&world](const Vec3& a, const Vec3& b) { return world.IsSegmentFree(a, b); }};
}

}  // namespace

void SensingParams::Describe(Archive& a) {
  a.Enum({"kind", "", "a range sensor all round, or a depth camera along body x"}, &kind,
         {{Kind::kOmni, "omni"}, {Kind::kCamera, "camera"}});
  a.Number({"range", "m", "how far the sensor sees"}, &range, 0.1, 1000);
  a.Degrees({"fov", "deg", "the camera's horizontal field (a RealSense D435's depth: 87)"},
            &fov_horizontal, 1, 359);
  a.Degrees({"fov_vertical", "deg", "the camera's vertical field"}, &fov_vertical, 1, 179);
  a.Number({"rate", "Hz", "updates per second (divides the physics rate)"}, &rate, 0.1, 1000);
}

void SensingParams::Validate() const { ValidateFields(*this, "sensing"); }

void ReplanParams::Describe(Archive& a) {
  a.Number({"horizon", "s", "ahead of the vehicle, where the new trajectory starts"}, &horizon, 0,
           5);
  a.Integer({"iterations", "", "RRT* iterations after its first solution, per leg"}, &iterations, 0,
            10000000);
  a.Integer({"search_iterations", "", "RRT* iterations for a first solution, per leg, at most"},
            &search_iterations, 1, 10000000);
  a.Number({"time_budget", "s", "wall time per leg: a safety cap, not the budget"}, &time_budget,
           1e-3, 10);
  a.Integer({"max_attempts", "", "attempts while braked before the flight gives up"}, &max_attempts,
            1, 1000000);
}

void ReplanParams::Validate() const { ValidateFields(*this, "replan"); }

double BrakingDeceleration(double max_tilt) { return 0.6 * kGravity * std::tan(max_tilt); }

double SensingSpeedLimit(const SensingParams& sensing, const ReplanParams& replan,
                         double deceleration, double margin) {
  const double tau = 1.0 / sensing.rate + replan.horizon + 0.1;
  const double distance = std::max(0.05, sensing.range - margin);
  const double a = deceleration;
  return -a * tau + std::sqrt(a * a * tau * tau + 2 * a * distance);
}

std::vector<bool> UnknownBoxes(const Map& map, const std::vector<int>& indices, double fraction,
                               std::uint64_t seed) {
  std::vector<bool> unknown(map.boxes.size(), false);
  for (const int i : indices) {
    if (i < 0 || i >= static_cast<int>(map.boxes.size())) {
      throw std::invalid_argument("unknown: box " + std::to_string(i) + " is not in the map (" +
                                  std::to_string(map.boxes.size()) + " boxes, from 0)");
    }
    unknown[static_cast<size_t>(i)] = true;
  }
  if (fraction > 0) {
    std::vector<size_t> order(map.boxes.size());
    std::iota(order.begin(), order.end(), 0);
    std::mt19937_64 rng(StreamSeed(seed, SeedStream::kUnknownBoxes));
    std::shuffle(order.begin(), order.end(), rng);
    const size_t count = static_cast<size_t>(std::lround(fraction * map.boxes.size()));
    for (size_t k = 0; k < count && k < order.size(); ++k) unknown[order[k]] = true;
  }
  return unknown;
}

Map KnownMap(const Map& map, const std::vector<bool>& unknown) {
  Map known = map;
  known.boxes.clear();
  for (size_t i = 0; i < map.boxes.size(); ++i) {
    if (i >= unknown.size() || !unknown[i]) known.boxes.push_back(map.boxes[i]);
  }
  return known;
}

bool SeesBox(const SensingParams& sensing, const State& state, const Aabb& box) {
  const Vec3 c = state.p_W;
  const Vec3 nearest = c.cwiseMax(box.min).cwiseMin(box.max);
  if ((nearest - c).norm() > sensing.range) return false;
  if (sensing.kind == SensingParams::Kind::kOmni) return true;
  // a depth camera along the body's x axis: any sampled point of the box in range and view
  const Quat q = state.q_WB.conjugate();
  const auto in_view = [&](const Vec3& p) {
    const Vec3 d = q * (p - c);
    if ((p - c).norm() > sensing.range || d.x() <= 0) return false;
    return std::abs(std::atan2(d.y(), d.x())) <= 0.5 * sensing.fov_horizontal &&
           std::abs(std::atan2(d.z(), d.head<2>().norm())) <= 0.5 * sensing.fov_vertical;
  };
  if (box.Contains(c) || in_view(nearest)) return true;
  constexpr int kGrid = 6;  // points per side of each face
  const Vec3 size = box.Size();
  for (int axis = 0; axis < 3; ++axis) {
    for (const double side : {0.0, 1.0}) {
      for (int i = 0; i <= kGrid; ++i) {
        for (int j = 0; j <= kGrid; ++j) {
          Vec3 f;
          f[axis] = side;
          f[(axis + 1) % 3] = static_cast<double>(i) / kGrid;
          f[(axis + 2) % 3] = static_cast<double>(j) / kGrid;
          if (in_view(box.min + size.cwiseProduct(f))) return true;
        }
      }
    }
  }
  return false;
}

Replanner::Replanner(const Map& map, const std::vector<bool>& unknown,
                     const CollisionParams& planning, const CollisionParams& trajectory,
                     const PlannerConfig& planner, const GeneratorConfig& generator,
                     const SensingParams& sensing, const ReplanParams& replan,
                     std::vector<Vec3> goals, std::vector<Vec3> path, std::uint64_t seed)
    : map_(map),
      unknown_(unknown),
      known_(map.boxes.size(), true),
      planning_(planning),
      trajectory_(trajectory),
      planner_(planner),
      params_(generator.params),
      generator_(MakeGenerator(generator)),
      minsnap_(MakeGenerator({"minsnap", generator.params, {}})),
      sensing_(sensing),
      replan_(replan),
      goals_(std::move(goals)),
      path_(std::move(path)),
      seed_(seed),
      revealed_at_(map.boxes.size(), -1.0) {
  sensing_.Validate();
  replan_.Validate();
  for (size_t i = 0; i < unknown_.size() && i < known_.size(); ++i) known_[i] = !unknown_[i];
  Rebuild();
}

void Replanner::Rebuild() {
  std::vector<bool> hidden(known_.size());
  for (size_t i = 0; i < known_.size(); ++i) hidden[i] = !known_[i];
  const Map known = KnownMap(map_, hidden);
  planner_world_.emplace(known, planning_);
  trajectory_world_.emplace(known, trajectory_);
}

int Replanner::unknown_count() const {
  return static_cast<int>(std::count(unknown_.begin(), unknown_.end(), true));
}

int Replanner::revealed_count() const {
  return static_cast<int>(
      std::count_if(revealed_at_.begin(), revealed_at_.end(), [](double t) { return t >= 0; }));
}

std::optional<Reference> Replanner::Update(double t, double tr, const State& state,
                                           int goals_reached, const Reference& current) {
  if (t + 1e-9 < next_sense_) return std::nullopt;
  while (next_sense_ <= t + 1e-9) next_sense_ += 1.0 / sensing_.rate;
  std::vector<size_t> newly;
  for (size_t i = 0; i < map_.boxes.size(); ++i) {
    if (known_[i] || !SeesBox(sensing_, state, map_.boxes[i].extent)) continue;
    known_[i] = true;
    revealed_at_[i] = t;
    newly.push_back(i);
  }
  if (!newly.empty()) Rebuild();
  if (braking_) {
    if (attempts_ >= replan_.max_attempts) return std::nullopt;
    return Replan(t, tr, goals_reached, current, "retry after braking");
  }
  if (newly.empty()) return std::nullopt;
  // does the rest of the reference now leave free space?
  constexpr double kStep = 0.02;  // [s]
  Vec3 previous = current.evaluate(std::min(tr, current.duration), kPosition);
  for (double s = tr + kStep;; s += kStep) {
    const double at = std::min(s, current.duration);
    const Vec3 p = current.evaluate(at, kPosition);
    if (!trajectory_world_->IsSegmentFree(previous, p)) {
      // the newly revealed box nearest the blocked point triggered it
      size_t trigger = newly.front();
      double best = std::numeric_limits<double>::infinity();
      for (const size_t i : newly) {
        const Aabb& b = map_.boxes[i].extent;
        const double d = (p.cwiseMax(b.min).cwiseMin(b.max) - p).norm();
        if (d < best) {
          best = d;
          trigger = i;
        }
      }
      return Replan(t, tr, goals_reached, current, map_.boxes[trigger].name);
    }
    previous = p;
    if (at >= current.duration) break;
  }
  return std::nullopt;
}

std::optional<Reference> Replanner::Replan(double t, double tr, int goals_reached,
                                           const Reference& current, const std::string& trigger) {
  const Clock::time_point begin = Clock::now();
  ReplanEvent event;
  event.t = t;
  event.trigger = trigger;
  // the state the new trajectory starts from: the reference's, a horizon ahead (nearer when
  // the box just seen stands there)
  double th = std::min(tr + replan_.horizon, current.duration);
  for (const double part : {0.5, 0.0}) {
    if (trajectory_world_->IsPointFree(current.evaluate(th, kPosition))) break;
    th = std::min(tr + part * replan_.horizon, current.duration);
  }
  StartState start;
  start.p_W = current.evaluate(th, kPosition);
  if (th < current.duration) {
    start.v_W = current.evaluate(th, kVelocity);
    start.a_W = current.evaluate(th, kAcceleration);
    start.j_W = current.evaluate(th, kJerk);
  }
  for (double s = th; s < current.duration; s += 0.05) {
    event.abandoned.push_back(current.evaluate(s, kPosition));
  }
  const auto plan_leg = [&](const Vec3& from, const Vec3& to, std::uint64_t salt,
                            std::vector<Vec3>* out) {
    // the start may lie within the planner's clearance of a box just seen: the trajectory's
    // world (less clearance) decides there
    const CollisionWorld& world =
        planner_world_->IsPointFree(from) ? *planner_world_ : *trajectory_world_;
    const Validity validity{
        [&world](const Vec3& p) { return world.IsPointFree(p); },
        [&world](const Vec3& a, const Vec3& b) { return world.IsSegmentFree(a, b); }};
    // the flight's planner, through its seam; RRT* to [replan]'s counts
    PlannerConfig config = planner_;
    const std::uint64_t seed = seed_ + 7919ULL * (events_.size() + 1) + salt;
    if (config.kind == "rrt_star") {
      RrtStarParams rrt = config.params.GetOr<RrtStarParams>();
      rrt.time_budget = replan_.time_budget;
      rrt.max_iterations = replan_.iterations;
      rrt.max_search_iterations = replan_.search_iterations;
      rrt.record_tree = false;
      rrt.seed = seed;
      config.params = PluginParameters::Of(rrt);
    }
    const PlanResult leg =
        MakePlanner(config, PlannerContext{world.free_bounds(), validity, seed})->Plan(from, to);
    event.time_capped |= leg.stats.time_capped;
    if (leg.status != PlanStatus::kSolved) return false;
    out->insert(out->end(), leg.path.begin() + 1, leg.path.end());
    return true;
  };
  const Clock::time_point planning = Clock::now();
  std::vector<Vec3> path = {start.p_W};
  bool found = false;
  // first, the local repair: to the first vertex of the path beyond the blocked stretch from
  // which the rest of the path is free (and no goal is skipped)
  {
    const CollisionWorld& world = *planner_world_;
    size_t nearest = 0;  // the path's vertex nearest the start
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < path_.size(); ++i) {
      const double d = (path_[i] - start.p_W).norm();
      if (d < best) {
        best = d;
        nearest = i;
      }
    }
    size_t rejoin = path_.size();
    for (size_t j = path_.size(); j-- > nearest + 1;) {
      if (!world.IsPointFree(path_[j])) break;
      if (j + 1 < path_.size() && !world.IsSegmentFree(path_[j], path_[j + 1])) break;
      rejoin = j;
    }
    bool skips_goal = false;
    for (size_t i = nearest + 1; i < rejoin && i < path_.size(); ++i) {
      for (size_t g = static_cast<size_t>(std::max(0, goals_reached)); g + 1 < goals_.size(); ++g) {
        if ((path_[i] - goals_[g]).norm() < 1e-6) skips_goal = true;
      }
    }
    if (rejoin < path_.size() && !skips_goal && plan_leg(start.p_W, path_[rejoin], 0, &path)) {
      path.insert(path.end(), path_.begin() + static_cast<long>(rejoin) + 1, path_.end());
      found = true;
    }
  }
  // otherwise RRT* leg by leg through the goals still ahead
  if (!found) {
    std::vector<Vec3> stops = {start.p_W};
    for (size_t g = static_cast<size_t>(std::max(0, goals_reached)); g < goals_.size(); ++g) {
      stops.push_back(goals_[g]);
    }
    path = {start.p_W};
    found = stops.size() >= 2;
    for (size_t leg = 1; leg < stops.size() && found; ++leg) {
      found = plan_leg(stops[leg - 1], stops[leg], leg, &path);
    }
  }
  event.planning_time = Seconds(planning);
  const auto replaced_by = [&event](const PiecewiseTrajectory& t) {
    for (double s = 0; s <= t.duration() + 1e-9; s += 0.05) {
      event.replacement.push_back(t.Evaluate3(s, kPosition));
      event.replacement_speeds.push_back(t.Evaluate3(s, kVelocity).norm());
    }
  };
  const auto done = [&](std::optional<Reference> reference, const std::string& outcome) {
    event.outcome = outcome;
    event.latency = Seconds(begin);
    // a retry while braked is recorded only when it succeeds
    if (trigger != "retry after braking" || reference) events_.push_back(event);
    return reference;
  };
  if (found) {
    event.path_length = PathLength(path);
    const Clock::time_point solving = Clock::now();
    const TrajectoryResult next = Continue(start, path);
    event.solve_time = Seconds(solving);
    if (next.status == TrajectoryStatus::kSolved) {
      braking_ = false;
      attempts_ = 0;
      path_ = path;
      replaced_by(next.trajectory);
      return done(Splice(current, th, next.trajectory),
                  trigger == "retry after braking" ? "replanned after braking" : "replanned");
    }
  }
  ++attempts_;
  if (braking_) return done(std::nullopt, "braked, still searching");
  // brake: to rest along the current direction of travel, as far as the known world allows
  braking_ = true;
  const double speed = start.v_W.norm();
  const std::string why = found ? "no trajectory" : "no path";
  if (speed < 1e-3) return done(std::nullopt, why);
  // brake: to rest along the current direction of travel, at the braking distance (longer
  // while the vehicle still accelerates forward); when that is infeasible further, and when
  // the known world has no room for it nearer
  const Vec3 direction = start.v_W / speed;
  const double decel = BrakingDeceleration(params_.max_tilt);
  const double forward = std::max(0.0, start.a_W.dot(direction));                 // [m/s^2]
  const double distance = speed * speed / (2 * decel) * (1.0 + forward / decel);  // [m]
  TrajectoryResult brake;
  for (const double factor : {1.0, 1.6, 2.5, 0.7, 0.5}) {
    const Vec3 stop = start.p_W + std::max(0.05, factor * distance) * direction;
    if (!trajectory_world_->IsSegmentFree(start.p_W, stop)) continue;
    brake = Continue(start, {start.p_W, stop});
    if (brake.status == TrajectoryStatus::kSolved) break;
  }
  if (brake.status != TrajectoryStatus::kSolved) {
    return done(std::nullopt, why + ", and no room to brake");
  }
  replaced_by(brake.trajectory);
  return done(Splice(current, th, brake.trajectory),
              found ? "braking (no trajectory)" : "braking (no path)");
}

TrajectoryResult Replanner::Continue(const StartState& start, const std::vector<Vec3>& path) const {
  const TrajectoryWorld view = ViewOf(*trajectory_world_);
  if (std::optional<TrajectoryResult> next = generator_->Continue(start, path, view)) return *next;
  return *minsnap_->Continue(start, path, view);
}

}  // namespace aerobox
