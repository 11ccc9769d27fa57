// The learning environments' worlds: a batch's world i is a lone world seeded s + i, whatever
// the threads; actions are checked before any world steps; the hover task's start, reward and
// ends are those its parameters say.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>
#include <vector>

#include "envs/env_batch.h"

namespace aerobox {
namespace {

struct Rows {
  std::vector<float> obs;
  std::vector<double> rewards;
  std::vector<std::uint8_t> ends;
};

// `steps` of `n` worlds seeded 100 + i, with actions from a fixed sequence.
Rows Fly(const EnvParams& params, int n, int threads, int steps) {
  EnvBatch batch(params, n, threads);
  const int d = params.ObservationSize();
  Rows rows;
  std::vector<float> obs(static_cast<size_t>(n * d));
  std::vector<double> actions(static_cast<size_t>(n * 4)), rewards(n), terms(n * 5);
  std::vector<std::uint8_t> terminated(n), truncated(n);
  std::vector<std::optional<std::uint64_t>> seeds;
  for (int i = 0; i < n; ++i) seeds.emplace_back(100 + i);
  batch.Reset(seeds, obs.data());
  for (int s = 0; s < steps; ++s) {
    for (size_t j = 0; j < actions.size(); ++j) actions[j] = std::sin(0.37 * s + 1.3 * j) * 0.9;
    batch.Step(actions.data(), obs.data(), rewards.data(), terminated.data(), truncated.data(),
               terms.data());
    rows.obs.insert(rows.obs.end(), obs.begin(), obs.end());
    rows.rewards.insert(rows.rewards.end(), rewards.begin(), rewards.end());
    for (int i = 0; i < n; ++i) rows.ends.push_back(terminated[i] | (truncated[i] << 1));
  }
  return rows;
}

EnvParams Short() {
  EnvParams p;
  p.episode_time = 0.3;
  return p;
}

TEST_CASE("the number of threads changes nothing") {
  const Rows one = Fly(Short(), 5, 1, 80), two = Fly(Short(), 5, 2, 80),
             four = Fly(Short(), 5, 4, 80);
  CHECK(one.obs == two.obs);
  CHECK(one.obs == four.obs);
  CHECK(one.rewards == four.rewards);
  CHECK(one.ends == four.ends);
  int ended = 0;
  for (std::uint8_t e : one.ends) ended += e != 0;
  CHECK(ended >= 5);  // episodes ended and the worlds were reset on the next step
}

TEST_CASE("the rigid backend: threads and the batch's size change nothing") {
  EnvParams rigid = Short();
  rigid.backend = "rigid";
  const Rows one = Fly(rigid, 7, 1, 60), two = Fly(rigid, 7, 2, 60), three = Fly(rigid, 3, 2, 60);
  CHECK(one.obs == two.obs);
  CHECK(one.rewards == two.rewards);
  CHECK(one.ends == two.ends);
  // the first 3 worlds of 7 are the 3 worlds of a batch of 3 (seeded alike)
  const size_t d = static_cast<size_t>(rigid.ObservationSize());
  for (size_t s = 0; s < 60; ++s) {
    CHECK(std::equal(three.obs.begin() + static_cast<long>(s * 3 * d),
                     three.obs.begin() + static_cast<long>((s + 1) * 3 * d),
                     one.obs.begin() + static_cast<long>(s * 7 * d)));
  }
  // and the rigid backend's worlds fly as MuJoCo's (the same seeds and actions)
  const Rows mujoco = Fly(Short(), 7, 2, 60);
  CHECK(mujoco.ends == one.ends);
  double largest = 0.0;
  for (size_t i = 0; i < one.obs.size(); ++i) {
    largest = std::max(largest, static_cast<double>(std::abs(one.obs[i] - mujoco.obs[i])));
  }
  CHECK(largest < 1e-4);  // float observations of states within rounding
}

TEST_CASE("physics_rate sets each backend's step, and a step still holds the control period") {
  for (const char* backend : {"mujoco", "rigid"}) {
    CAPTURE(backend);
    EnvParams params;
    params.backend = backend;
    params.physics_rate = 500;
    EnvBatch batch(params, 1, 1);
    CHECK(batch.world(0).physics().timestep() == doctest::Approx(0.002).epsilon(1e-12));
    std::vector<float> obs(static_cast<size_t>(params.ObservationSize()));
    batch.Reset({1}, obs.data());
    const double before = batch.world(0).physics().time();
    const double hover[4] = {0.0, 0.0, 0.0, 0.0};
    batch.world(0).Step(hover, obs.data());
    CHECK(batch.world(0).physics().time() - before == doctest::Approx(0.01).epsilon(1e-9));
    CHECK(batch.world(0).time() == doctest::Approx(0.01));
  }
}

TEST_CASE("a bad action is refused before any world steps") {
  EnvParams params;
  EnvBatch batch(params, 2, 2);
  std::vector<float> obs(static_cast<size_t>(2 * params.ObservationSize()));
  batch.Reset({1, 2}, obs.data());
  const double x0 = batch.world(0).state().p_W.x();
  std::vector<double> actions = {0, 0, 0, 0, 0, 0, 1.01, 0};
  double rewards[2], terms[10];
  std::uint8_t te[2], tr[2];
  CHECK_THROWS_WITH_AS(batch.Step(actions.data(), obs.data(), rewards, te, tr, terms),
                       "action[1][2] = 1.01: expected a number in [-1, 1]", std::invalid_argument);
  CHECK(batch.world(0).time() == 0.0);
  CHECK(batch.world(0).state().p_W.x() == x0);
}

TEST_CASE("the start stays within its ranges, and the reward's terms are its weights") {
  EnvParams params;
  params.start_radius = 0.5;
  params.start_speed = 0.2;
  EnvBatch batch(params, 1, 1);
  std::vector<float> obs(static_cast<size_t>(params.ObservationSize()));
  for (std::uint64_t seed = 0; seed < 50; ++seed) {
    batch.Reset({seed}, obs.data());
    const State& s = batch.world(0).state();
    CHECK((s.p_W - params.target).norm() <= 0.5 + 1e-9);
    CHECK(s.v_W.norm() <= 0.2 + 1e-9);
    const Vec3 z_B = s.q_WB * Vec3::UnitZ();
    CHECK(std::acos(std::min(1.0, z_B.z())) <= params.start_tilt + 1e-9);
  }
  const double hover[4] = {0.0, 0.0, 0.0, 0.0};
  const EnvStep step = batch.world(0).Step(hover, obs.data());
  const State& s = batch.world(0).state();
  CHECK(step.terms[0] == 1.0);
  CHECK(step.terms[1] == doctest::Approx(-(s.p_W - params.target).norm()));
  CHECK(step.terms[2] == doctest::Approx(-0.1 * s.v_W.norm()));
  CHECK(step.terms[4] == 0.0);
  CHECK(step.reward == doctest::Approx(step.terms[0] + step.terms[1] + step.terms[2] +
                                       step.terms[3] + step.terms[4]));
}

TEST_CASE("the floor ends an episode as a crash, and time as a truncation") {
  EnvParams params;
  params.action = "thrusts";
  params.start_tilt = 0.0;
  params.start_rate = 0.0;
  EnvBatch batch(params, 1, 1);
  std::vector<float> obs(static_cast<size_t>(params.ObservationSize()));
  batch.Reset({3}, obs.data());
  const double off[4] = {-1, -1, -1, -1};  // the rotors stop: it falls
  EnvStep step;
  int n = 0;
  while (!step.terminated && !step.truncated && n < 300)
    step = batch.world(0).Step(off, obs.data()), ++n;
  CHECK(step.terminated);
  CHECK(batch.world(0).time() < 1.0);  // at most 2.5 m in free fall
  params.episode_time = 0.05;
  EnvBatch quick(params, 1, 1);
  quick.Reset({3}, obs.data());
  const double mid[4] = {0, 0, 0, 0};
  for (int i = 0; i < 4; ++i) CHECK_FALSE(quick.world(0).Step(mid, obs.data()).truncated);
  const EnvStep last = quick.world(0).Step(mid, obs.data());
  CHECK(last.truncated);
  CHECK_FALSE(last.terminated);
}

TEST_CASE("bad parameters name the field") {
  const std::pair<std::function<void(EnvParams*)>, const char*> cases[] = {
      {[](EnvParams* p) { p->control_rate = 300; }, "control_rate 300"},
      {[](EnvParams* p) { p->backend = "bullet"; }, "env.backend"},
      {[](EnvParams* p) { p->physics_rate = 450; }, "physics_rate 450"},
      {[](EnvParams* p) { p->action = "motors"; }, "env.action"},
  };
  for (const auto& [change, message] : cases) {
    EnvParams params;
    change(&params);
    CHECK_THROWS_WITH_AS(EnvBatch(params, 1, 1), doctest::Contains(message), std::invalid_argument);
  }
}

}  // namespace
}  // namespace aerobox
