// The wind: gust shapes, Dryden turbulence's statistics against MIL-F-8785C, and the drag it
// causes.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "disturbance/aero.h"
#include "disturbance/wind.h"

namespace aerobox {
namespace {

// The sample autocorrelation of x at a lag of `lag` samples, normalised by the variance.
double Correlation(const std::vector<double>& x, long lag) {
  double mean = 0.0;
  for (const double v : x) mean += v;
  mean /= static_cast<double>(x.size());
  double variance = 0.0, product = 0.0;
  for (size_t i = 0; i < x.size(); ++i) variance += (x[i] - mean) * (x[i] - mean);
  for (size_t i = 0; i + static_cast<size_t>(lag) < x.size(); ++i)
    product += (x[i] - mean) * (x[i + static_cast<size_t>(lag)] - mean);
  return product / variance;
}

double StandardDeviation(const std::vector<double>& x) {
  double mean = 0.0, square = 0.0;
  for (const double v : x) mean += v;
  mean /= static_cast<double>(x.size());
  for (const double v : x) square += (v - mean) * (v - mean);
  return std::sqrt(square / static_cast<double>(x.size()));
}

// The spatial lag [m] at which the correlation first falls to `level`, by bisection over the
// lag in samples (the correlation falls monotonically before it).
double LagAt(const std::vector<double>& x, double level, double metres_per_sample) {
  long low = 1, high = 1;
  while (Correlation(x, high) > level) high *= 2;
  while (high - low > 1) {
    const long mid = (low + high) / 2;
    (Correlation(x, mid) > level ? low : high) = mid;
  }
  return static_cast<double>(high) * metres_per_sample;
}

TEST_CASE("the scale lengths follow MIL-F-8785C at low altitude") {
  // h = 10 m = 32.8 ft: L_u = 32.8 / (0.177 + 0.000823 * 32.8)^1.2 ft
  const Vec3 l = DrydenScaleLengths(10.0);
  const double h = 10.0 / 0.3048;
  CHECK(l.x() == doctest::Approx(h / std::pow(0.177 + 0.000823 * h, 1.2) * 0.3048));
  CHECK(l.y() == doctest::Approx(l.x()));
  CHECK(l.z() == doctest::Approx(10.0));
  CHECK(DrydenScaleLengths(0.0).z() == doctest::Approx(1.0));  // clamped to the model's range
  // intensities: sigma_w = 0.1 W20, the horizontal ones larger near the ground
  const Vec3 sigma = DrydenIntensities(10.0, 10.0);
  CHECK(sigma.z() == doctest::Approx(1.0));
  CHECK(sigma.x() == doctest::Approx(1.0 / std::pow(0.177 + 0.000823 * h, 0.4)));
  CHECK(sigma.x() > 1.5);
}

TEST_CASE("Dryden turbulence has the intensity and the correlation length asked for") {
  // the first-order u component correlates as exp(-xi / L): 1/e at xi = L; the second-order v
  // and w as (1 - xi / 2L) exp(-xi / L): 0.5/e at xi = L
  const Vec3 sigma(1.5, 1.0, 0.5);
  for (const double airspeed : {2.0, 8.0}) {
    for (const double height : {2.0, 20.0}) {
      CAPTURE(airspeed);
      CAPTURE(height);
      DrydenTurbulence turbulence(sigma, 7);
      const Vec3 length = DrydenScaleLengths(height);
      // 40 samples per correlation time of the shortest component (w), 4000 correlation
      // times of the longest (u)
      const double dt = length.z() / airspeed / 40;
      const long n = static_cast<long>(4000 * length.x() / airspeed / dt);
      std::vector<double> u(n), v(n), w(n);
      for (long i = 0; i < n; ++i) {
        const Vec3 s = turbulence.Step(dt, airspeed, height);
        u[i] = s.x();
        v[i] = s.y();
        w[i] = s.z();
      }
      CHECK(StandardDeviation(u) == doctest::Approx(sigma.x()).epsilon(0.10));
      CHECK(StandardDeviation(v) == doctest::Approx(sigma.y()).epsilon(0.10));
      CHECK(StandardDeviation(w) == doctest::Approx(sigma.z()).epsilon(0.10));
      const double per_sample = airspeed * dt;  // [m] flown per sample
      CHECK(LagAt(u, std::exp(-1.0), per_sample) == doctest::Approx(length.x()).epsilon(0.10));
      CHECK(LagAt(v, 0.5 * std::exp(-1.0), per_sample) ==
            doctest::Approx(length.y()).epsilon(0.10));
      CHECK(LagAt(w, 0.5 * std::exp(-1.0), per_sample) ==
            doctest::Approx(length.z()).epsilon(0.10));
    }
  }
}

TEST_CASE("the turbulence's statistics do not depend on the step") {
  // exact discretisation: 1 ms and 50 ms steps give the same spread
  for (const double dt : {0.001, 0.05}) {
    DrydenTurbulence turbulence(Vec3(1, 1, 1), 3);
    const long n = static_cast<long>(2000.0 / dt);  // 5000 correlation times of w
    std::vector<double> w;
    for (long i = 0; i < n; ++i) w.push_back(turbulence.Step(dt, 5.0, 2.0).z());
    CHECK(StandardDeviation(w) == doctest::Approx(1.0).epsilon(0.05));
  }
}

TEST_CASE("the same seed gives the same turbulence, another seed another") {
  DrydenTurbulence a(Vec3(1, 1, 1), 11), b(Vec3(1, 1, 1), 11), c(Vec3(1, 1, 1), 12);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 x = a.Step(0.001, 3.0, 2.0);
    CHECK(x == b.Step(0.001, 3.0, 2.0));
    if (i == 999) CHECK(x != c.Step(0.001, 3.0, 2.0));
  }
}

TEST_CASE("a gust rises as 1 - cos, holds its peak and falls back") {
  Gust g;
  g.start = 1.0;
  g.rise = 0.5;
  g.duration = 3.0;
  g.peak = 4.0;
  g.direction = Vec3(0, 2, 0);
  CHECK(g.At(0.9).norm() == 0.0);
  CHECK(g.At(1.25).y() == doctest::Approx(2.0));  // half way up
  CHECK(g.At(2.0).y() == doctest::Approx(4.0));
  CHECK(g.At(3.75).y() == doctest::Approx(2.0));  // half way down
  CHECK(g.At(4.1).norm() == 0.0);
  for (double t = 0.9; t < 4.1; t += 0.001) CHECK((g.At(t + 0.001) - g.At(t)).norm() < 0.02);
}

TEST_CASE("the wind field adds the mean, the gusts and the turbulence in the wind's frame") {
  WindParams p;
  p.mean = Vec3(0, 3, 0);  // from the south: u is world y, v world -x
  p.turbulence = Turbulence::kDryden;
  p.intensity = Vec3(1.0, 0.0, 0.0);  // along the wind only
  WindField field(p, 5);
  double across = 0.0;
  for (int i = 0; i < 1000; ++i) {
    const Vec3 w = field.Step(i * 0.01, 0.01, 2.0, Vec3::Zero());
    across = std::max(across, std::abs(w.x()) + std::abs(w.z()));
  }
  CHECK(across < 1e-12);
  WindParams bad;
  bad.gusts.push_back(Gust());
  bad.gusts[0].duration = 0.5;  // shorter than its rise and fall
  CHECK_THROWS_WITH_AS(bad.Validate(), doctest::Contains("gusts[0].duration"),
                       std::invalid_argument);
}

TEST_CASE("drag: quadratic body drag and rotor drag proportional to thrust") {
  QuadParams v;
  State s;
  s.v_W = Vec3(2, 0, 0);
  const Vec4 hover = Vec4::Constant(v.HoverThrustPerRotor());
  AeroParams body{true, false}, rotor{false, true};
  const Wrench b = AerodynamicWrench(v, body, s, hover, Vec3::Zero());
  CHECK(b.force_W.x() == doctest::Approx(-v.body_drag.x() * 4.0));
  CHECK(b.force_W.tail<2>().norm() < 1e-12);
  // the same airspeed from the wind instead of the motion
  State still;
  const Wrench windy = AerodynamicWrench(v, body, still, hover, Vec3(-2, 0, 0));
  CHECK((windy.force_W - b.force_W).norm() < 1e-12);
  const Wrench r1 = AerodynamicWrench(v, rotor, s, hover, Vec3::Zero());
  const Wrench r2 = AerodynamicWrench(v, rotor, s, 2 * hover, Vec3::Zero());
  CHECK(r1.force_W.x() == doctest::Approx(-v.rotor_drag.x() * 4 * v.HoverThrustPerRotor() * 2));
  CHECK(r2.force_W.x() == doctest::Approx(2 * r1.force_W.x()));
  CHECK(r1.torque_W.norm() < 1e-12);  // symmetric rotors, no rotation: no moment
  // spinning, each rotor meets its own airspeed w x r: the drag damps the rotation
  State spinning;
  spinning.w_B = Vec3(0, 0, 5);
  const Wrench spin = AerodynamicWrench(v, rotor, spinning, hover, Vec3::Zero());
  CHECK(spin.torque_W.z() < 0);
  CHECK(spin.force_W.norm() < 1e-12);
  const Wrench none = AerodynamicWrench(v, AeroParams{}, s, hover, Vec3::Zero());
  CHECK(none.force_W.norm() == 0.0);
}

}  // namespace
}  // namespace aerobox
