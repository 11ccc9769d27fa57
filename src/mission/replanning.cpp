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
#include "common/wall_clock.h"
#include "planning/path_simplify.h"
#include "planning/rrt_star.h"

namespace aerobox {
namespace {

using Clock = std::chrono::steady_clock;

const char* const kRetry = "retry after braking";
// the trajectory within the stopping distance meets space the depth camera has not seen
const char* const kUnknownAhead = "unknown ahead";
// the trajectory ends where the camera had seen the path to; it has seen further since
const char* const kSeenFurther = "seen further";

constexpr double kNear = 0.3;       // [m] nearer than this the camera cannot see beside the vehicle
constexpr double kBackoff = 0.1;    // [m] a committed trajectory's end before the unseen
constexpr double kExtend = 0.5;     // [m] seen beyond it: the trajectory is extended
constexpr double kWalkStep = 0.05;  // [m] along a path, half a default cell

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
  a.Enum({"kind", "",
          "a range sensor all round, a field of view along body x (both reveal whole boxes, "
          "through walls), or a depth camera that builds an occupancy map"},
         &kind, {{Kind::kOmni, "omni"}, {Kind::kCamera, "camera"}, {Kind::kDepth, "depth"}});
  a.Number({"range", "m", "how far the sensor sees"}, &range, 0.1, 1000);
  a.Degrees({"fov", "deg", "the camera's horizontal field (a RealSense D435's depth: 87)"},
            &fov_horizontal, 1, 359);
  a.Degrees({"fov_vertical", "deg", "the camera's vertical field"}, &fov_vertical, 1, 179);
  a.Number({"rate", "Hz", "updates per second (divides the controller's rate)"}, &rate, 0.1, 1000);
  camera.Describe(a);
  map.Describe(a);
}

void SensingParams::Validate() const {
  ValidateFields(*this, "sensing");
  if (kind == Kind::kDepth) Camera().Validate("sensing");
}

DepthCameraParams SensingParams::Camera() const {
  DepthCameraParams c = camera;
  c.fov_horizontal = fov_horizontal;
  c.fov_vertical = fov_vertical;
  c.range = range;
  return c;
}

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
      revealed_at_(map.boxes.size(), -1.0),
      revealed_distance_(map.boxes.size(), -1.0) {
  sensing_.Validate();
  replan_.Validate();
  for (size_t i = 0; i < unknown_.size() && i < known_.size(); ++i) known_[i] = !unknown_[i];
  if (sensing_.kind == SensingParams::Kind::kDepth) {
    for (const Box& box : map_.boxes) extents_.push_back(box.extent);
    camera_.emplace(sensing_.Camera(), StreamSeed(seed_, SeedStream::kDepthCamera));
    grid_ = std::make_shared<OccupancyGrid>(map_.bounds, sensing_.map);
    // a cell that rays grazing a face have cleared can still hold that face: with a map, every
    // clearance grows by half a cell
    planning_.clearance += 0.5 * sensing_.map.resolution;
    trajectory_.clearance += 0.5 * sensing_.map.resolution;
  }
  Rebuild();
}

void Replanner::Rebuild() {
  std::vector<bool> hidden(known_.size());
  for (size_t i = 0; i < known_.size(); ++i) hidden[i] = !known_[i];
  Map known = KnownMap(map_, hidden);
  if (grid_) {
    // the occupancy map's occupied cells, merged into boxes, are what the planner avoids
    for (const Aabb& cells : grid_->OccupiedBoxes(sensing_.map.columns)) {
      known.boxes.push_back({cells, Vec3::Constant(0.5), "occupied cells", 0});
    }
  }
  planner_world_.emplace(known, planning_);
  trajectory_world_.emplace(known, trajectory_);
}

bool Replanner::Sense(double t, const State& state, std::vector<size_t>* newly) {
  if (camera_) return SenseDepth(t, state, newly);
  for (size_t i = 0; i < map_.boxes.size(); ++i) {
    if (known_[i] || !SeesBox(sensing_, state, map_.boxes[i].extent)) continue;
    const Aabb& b = map_.boxes[i].extent;
    known_[i] = true;
    revealed_at_[i] = t;
    revealed_distance_[i] = (state.p_W.cwiseMax(b.min).cwiseMin(b.max) - state.p_W).norm();
    newly->push_back(i);
  }
  return !newly->empty();
}

bool Replanner::SenseDepth(double t, const State& state, std::vector<size_t>* newly) {
  Clock::time_point begin = Clock::now();
  auto captured = std::make_shared<DepthImage>(camera_->Capture(state, extents_, map_.bounds));
  depth_image_ = captured;
  const DepthImage& image = *captured;
  ++cost_.frames;
  cost_.capture += Seconds(begin);
  for (int v = 0; v < image.height; ++v) {
    for (int u = 0; u < image.width; ++u) {
      const size_t k = static_cast<size_t>(v * image.width + u);
      const int hit = image.hit[k];
      if (hit < 0 || image.depth[k] <= 0.0f || known_[static_cast<size_t>(hit)]) continue;
      const size_t i = static_cast<size_t>(hit);
      const double distance = (image.PointW(u, v) - image.origin_W).norm();
      if (revealed_at_[i] < 0) {
        revealed_at_[i] = t;
        newly->push_back(i);
      }
      if (revealed_at_[i] == t && (revealed_distance_[i] < 0 || distance < revealed_distance_[i])) {
        revealed_distance_[i] = distance;
      }
    }
  }
  // boxes known from the start are in the planner's world already: their points only clear
  // the space before them
  begin = Clock::now();
  const int added = grid_->Insert(image, sensing_.range, known_);
  cost_.fusion += Seconds(begin);
  if (added == 0) return false;
  begin = Clock::now();
  Rebuild();
  cost_.rebuild += Seconds(begin);
  return true;
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
  const bool changed = Sense(t, state, &newly);
  if (changed && !camera_) Rebuild();
  if (braking_) {
    if (attempts_ >= replan_.max_attempts) return std::nullopt;
    // at rest with nothing new known, an attempt would repeat the last one: the same start,
    // the same world and the same seed
    const long known = grid_ ? grid_->free_count() + grid_->occupied_count() : revealed_count();
    const bool still = state.v_W.norm() < 0.05;  // [m/s]
    if (still && retried_still_ && known == known_at_retry_) return std::nullopt;
    retried_still_ = still;
    known_at_retry_ = known;
    return Replan(t, tr, goals_reached, current, kRetry);
  }
  if (changed) {
    if (const std::optional<Vec3> blocked = FirstBlocked(current, tr)) {
      return Replan(t, tr, goals_reached, current, TriggerNear(*blocked, newly));
    }
  }
  if (grid_ && UnknownAhead(current, tr, state.v_W.norm())) {
    return Replan(t, tr, goals_reached, current, kUnknownAhead);
  }
  if (grid_ && SeenFurther(state.p_W)) return Replan(t, tr, goals_reached, current, kSeenFurther);
  return std::nullopt;
}

std::optional<Vec3> Replanner::FirstBlocked(const Reference& current, double tr) const {
  constexpr double kStep = 0.02;  // [s]
  Vec3 previous = current.evaluate(std::min(tr, current.duration), kPosition);
  for (double s = tr + kStep;; s += kStep) {
    const double at = std::min(s, current.duration);
    const Vec3 p = current.evaluate(at, kPosition);
    if (!trajectory_world_->IsSegmentFree(previous, p)) return p;
    previous = p;
    if (at >= current.duration) return std::nullopt;
  }
}

std::string Replanner::TriggerNear(const Vec3& p, std::vector<size_t> newly) const {
  if (newly.empty()) {
    // the depth camera's new cells belong to boxes seen before
    for (size_t i = 0; i < revealed_at_.size(); ++i) {
      if (revealed_at_[i] >= 0) newly.push_back(i);
    }
  }
  std::string name = "occupied cells";
  double best = std::numeric_limits<double>::infinity();
  for (const size_t i : newly) {
    const Aabb& b = map_.boxes[i].extent;
    const double d = (p.cwiseMax(b.min).cwiseMin(b.max) - p).norm();
    if (d < best) {
      best = d;
      name = map_.boxes[i].name;
    }
  }
  return name;
}

bool Replanner::UnknownAhead(const Reference& reference, double from, double speed) const {
  // what the vehicle needs to stop: the braking distance and the way it goes while the camera
  // reads and the replan starts
  const double decel = BrakingDeceleration(params_.max_tilt);
  const double reach =
      speed * speed / (2 * decel) + speed * (1.0 / sensing_.rate + replan_.horizon);
  constexpr double kStep = 0.02;  // [s]
  Vec3 previous = reference.evaluate(std::min(from, reference.duration), kPosition);
  double length = 0.0;
  for (double s = from + kStep; length <= reach; s += kStep) {
    const double at = std::min(s, reference.duration);
    const Vec3 p = reference.evaluate(at, kPosition);
    length += (p - previous).norm();
    previous = p;
    if (length >= kNear && length <= reach && !Seen(p)) return true;
    if (at >= reference.duration) break;
  }
  return false;
}

bool Replanner::Seen(const Vec3& p) const {
  // every cell the vehicle's box, grown by the trajectory's clearance, overlaps there (less a
  // centimetre: not the cells beyond ones it just touches): its centre's alone lets the body
  // reach into the unknown beside a free cell (at 0.1 m cells, most of a Tello's width)
  const Vec3 half = trajectory_.Margin().array() - 0.01;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 sign(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1);
    if (grid_->At(p + sign.cwiseProduct(half)) == Occupancy::kUnknown) return false;
  }
  return true;
}

double Replanner::FirstUnseen(const std::vector<Vec3>& path, double from, double to,
                              bool* blocked) const {
  const auto stop = [&](const Vec3& p) {
    if (blocked && !trajectory_world_->IsPointFree(p)) return *blocked = true;
    return !Seen(p);
  };
  double arc = 0.0;  // [m] at path[i - 1]
  for (size_t i = 1; i < path.size(); ++i) {
    const Vec3 d = path[i] - path[i - 1];
    const double length = d.norm();
    for (double s = std::max(0.0, from - arc); s < length && arc + s <= to; s += kWalkStep) {
      if (stop(path[i - 1] + (s / length) * d)) return arc + s;
    }
    arc += length;
    if (arc > to) return std::numeric_limits<double>::infinity();
  }
  return stop(path.back()) ? arc : std::numeric_limits<double>::infinity();
}

bool Replanner::SeenFurther(const Vec3& p) const {
  if (!committed_) return true;  // the flight's first trajectory: not cut yet
  if (std::isinf(*committed_)) return false;
  // the path beyond the reference's end now blocked (the unseen was a box), or seen further;
  // the first kNear beyond the vehicle are its own
  const double here = ArcNearest(path_, p);
  const double seen = *committed_ + kBackoff + kExtend;
  bool blocked = false;
  const double unseen = FirstUnseen(path_, std::max(*committed_, here + kNear), seen, &blocked);
  // a vehicle at the reference's end creeps on by what it may count as its own
  const bool waiting = here > *committed_ - kBackoff && unseen - kBackoff > *committed_ + kBackoff;
  return unseen > seen || blocked || waiting;
}

std::optional<std::vector<Vec3>> Replanner::FindPath(const Vec3& start, int goals_reached,
                                                     ReplanEvent* event) const {
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
    event->time_capped |= leg.stats.time_capped;
    if (leg.status != PlanStatus::kSolved) return false;
    out->insert(out->end(), leg.path.begin() + 1, leg.path.end());
    return true;
  };
  // first, the local repair: to the first vertex of the path beyond the blocked stretch from
  // which the rest of the path is free (and no goal is skipped)
  std::vector<Vec3> path = {start};
  const size_t rejoin = Rejoin(start, goals_reached);
  if (rejoin < path_.size() && plan_leg(start, path_[rejoin], 0, &path)) {
    path.insert(path.end(), path_.begin() + static_cast<long>(rejoin) + 1, path_.end());
    return path;
  }
  // otherwise leg by leg through the goals still ahead
  std::vector<Vec3> stops = {start};
  for (size_t g = static_cast<size_t>(std::max(0, goals_reached)); g < goals_.size(); ++g) {
    stops.push_back(goals_[g]);
  }
  path = {start};
  if (stops.size() < 2) return std::nullopt;
  for (size_t leg = 1; leg < stops.size(); ++leg) {
    if (!plan_leg(stops[leg - 1], stops[leg], leg, &path)) return std::nullopt;
  }
  return path;
}

size_t Replanner::Rejoin(const Vec3& start, int goals_reached) const {
  const CollisionWorld& world = *planner_world_;
  size_t nearest = 0;  // the path's vertex nearest the start
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < path_.size(); ++i) {
    const double d = (path_[i] - start).norm();
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
  for (size_t i = nearest + 1; i < rejoin && i < path_.size(); ++i) {
    for (size_t g = static_cast<size_t>(std::max(0, goals_reached)); g + 1 < goals_.size(); ++g) {
      if ((path_[i] - goals_[g]).norm() < 1e-6) return path_.size();  // it would skip a goal
    }
  }
  return rejoin;
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
  const auto done = [&](std::optional<Reference> reference, const std::string& outcome) {
    event.outcome = outcome;
    event.latency = Seconds(begin);
    // a retry while braked is recorded only when it succeeds
    if (trigger != kRetry || reference) events_.push_back(event);
    return reference;
  };
  // unknown space within the stopping distance: brake, without searching
  const bool unknown_ahead = trigger == kUnknownAhead;
  std::optional<Continuation> next;
  if (!unknown_ahead) next = Continue(start, goals_reached, &event);
  if (next) {
    Reference spliced = Splice(current, th, next->trajectory);
    // braked before unknown space: go on only once the vehicle can stop before it
    if (grid_ && trigger == kRetry && UnknownAhead(spliced, th, start.v_W.norm())) {
      return done(std::nullopt, "braked, unknown ahead");
    }
    braking_ = false;
    attempts_ = 0;
    path_ = next->path;
    committed_ = next->committed;
    ReplacedBy(next->trajectory, &event);
    return done(std::move(spliced), trigger == kRetry ? "replanned after braking" : "replanned");
  }
  if (!unknown_ahead) ++attempts_;
  if (braking_) return done(std::nullopt, "braked, still searching");
  braking_ = true;
  const std::string why = unknown_ahead             ? "unknown ahead"
                          : event.path_length > 0.0 ? "no trajectory"
                                                    : "no path";
  if (start.v_W.norm() < 1e-3) return done(std::nullopt, why);
  const std::optional<PiecewiseTrajectory> brake = Brake(start);
  if (!brake) return done(std::nullopt, why + ", and no room to brake");
  ReplacedBy(*brake, &event);
  return done(Splice(current, th, *brake), "braking (" + why + ")");
}

void Replanner::ReplacedBy(const PiecewiseTrajectory& trajectory, ReplanEvent* event) {
  for (double s = 0; s <= trajectory.duration() + 1e-9; s += 0.05) {
    event->replacement.push_back(trajectory.Evaluate3(s, kPosition));
    event->replacement_speeds.push_back(trajectory.Evaluate3(s, kVelocity).norm());
  }
}

std::optional<PiecewiseTrajectory> Replanner::Brake(const StartState& start) const {
  // to rest along the current direction of travel, at the braking distance (longer while the
  // vehicle still accelerates forward); when that is infeasible further, and when the known
  // world has no room for it nearer; when the known world has no room for any, the stop at the
  // braking distance all the same: stopping short of what was just seen beats flying on into it
  const double speed = start.v_W.norm();
  const Vec3 direction = start.v_W / speed;
  const double decel = BrakingDeceleration(params_.max_tilt);
  const double forward = std::max(0.0, start.a_W.dot(direction));                 // [m/s^2]
  const double distance = speed * speed / (2 * decel) * (1.0 + forward / decel);  // [m]
  for (const double factor : {1.0, 1.6, 2.5, 0.7, 0.5}) {
    const Vec3 stop = start.p_W + std::max(0.05, factor * distance) * direction;
    if (!trajectory_world_->IsSegmentFree(start.p_W, stop)) continue;
    TrajectoryResult brake = Continue(start, {start.p_W, stop});
    if (brake.status == TrajectoryStatus::kSolved) return std::move(brake.trajectory);
  }
  const TrajectoryWorld anywhere{[](const Aabb&) { return true; },
                                 [](const Vec3&, const Vec3&) { return true; }};
  for (const double factor : {1.0, 1.6, 2.5}) {
    const std::vector<Vec3> path = {start.p_W,
                                    start.p_W + std::max(0.05, factor * distance) * direction};
    if (std::optional<TrajectoryResult> brake = minsnap_->Continue(start, path, anywhere)) {
      if (brake->status == TrajectoryStatus::kSolved) return std::move(brake->trajectory);
    }
  }
  return std::nullopt;
}

std::optional<Replanner::Continuation> Replanner::Continue(const StartState& start,
                                                           int goals_reached,
                                                           ReplanEvent* event) const {
  // a fast start needs room to turn: first the path from where braking along the travel would
  // stop, reached straight on, when that is free; then the path from the start itself
  std::vector<std::vector<Vec3>> heads = {{start.p_W}};
  const double speed = start.v_W.norm();
  if (speed > 0.5) {
    const Vec3 lead = start.p_W + speed / (2 * BrakingDeceleration(params_.max_tilt)) * start.v_W;
    if (planner_world_->IsSegmentFree(start.p_W, lead)) {
      heads.insert(heads.begin(), {start.p_W, lead});
    }
  }
  // a vehicle at rest within the clearance of cells seen after it stopped backs off first, to
  // the nearest point that keeps it: the world near the start is the vehicle's own there
  std::optional<Aabb> escape;
  if (speed < 0.1 && !trajectory_world_->IsPointFree(start.p_W)) {
    const std::optional<Vec3> out = NearestFree(start.p_W);
    if (!out) return std::nullopt;
    heads = {{start.p_W, *out}};
    escape = Aabb{start.p_W.cwiseMin(*out), start.p_W.cwiseMax(*out)};
  }
  for (const std::vector<Vec3>& head : heads) {
    const Clock::time_point planning = Clock::now();
    std::optional<std::vector<Vec3>> path = FindPath(head.back(), goals_reached, event);
    event->planning_time += Seconds(planning);
    if (!path) continue;
    path->insert(path->begin(), head.begin(), head.end() - 1);
    event->path_length = PathLength(*path);
    // with a depth camera, the trajectory ends at rest before the first space not seen: the
    // vehicle can always stop in what it has seen (the first kNear are the vehicle's own)
    const double unseen = grid_ ? FirstUnseen(*path, kNear, std::numeric_limits<double>::infinity())
                                : std::numeric_limits<double>::infinity();
    const double committed = unseen - kBackoff;
    const Clock::time_point solving = Clock::now();
    TrajectoryResult next =
        Continue(start, std::isinf(unseen) ? *path : PathHead(*path, committed), escape);
    event->solve_time += Seconds(solving);
    if (next.status == TrajectoryStatus::kSolved) {
      return Continuation{std::move(*path), std::move(next.trajectory), committed};
    }
  }
  return std::nullopt;
}

std::optional<Vec3> Replanner::NearestFree(const Vec3& p) const {
  for (const double radius : {0.05, 0.1, 0.15, 0.2, 0.3, 0.4}) {  // [m]
    for (int i = 0; i < 27; ++i) {
      const Vec3 d(i % 3 - 1, (i / 3) % 3 - 1, i / 9 - 1);
      if (d.isZero()) continue;
      const Vec3 q = p + radius * d.normalized();
      if (trajectory_world_->IsPointFree(q)) return q;
    }
  }
  return std::nullopt;
}

TrajectoryResult Replanner::Continue(const StartState& start, const std::vector<Vec3>& path,
                                     const std::optional<Aabb>& escape) const {
  TrajectoryWorld view = ViewOf(*trajectory_world_);
  if (escape) {
    // within the escape's box (grown by a few centimetres for the trajectory's curve), free
    const Aabb near{escape->min.array() - 0.05, escape->max.array() + 0.05};
    const CollisionWorld& world = *trajectory_world_;
    view.box_free = [&world, near](const Aabb& box) {
      return near.Contains(box.min) && near.Contains(box.max) ? true : world.IsBoxFree(box);
    };
    view.segment_free = [&world, near](const Vec3& a, const Vec3& b) {
      return near.Contains(a) && near.Contains(b) ? true : world.IsSegmentFree(a, b);
    };
  }
  if (std::optional<TrajectoryResult> next = generator_->Continue(start, path, view)) return *next;
  return *minsnap_->Continue(start, path, view);
}

}  // namespace aerobox
