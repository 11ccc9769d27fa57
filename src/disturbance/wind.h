// The air the vehicle flies in: a mean wind, discrete gusts and Dryden turbulence after
// MIL-F-8785C, seeded. Spatially uniform: the vehicle samples the field where it is.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "common/schema.h"
#include "common/types.h"

namespace aerobox {

// A discrete gust (as RotorS's gust: a start, a duration, a peak speed along a direction), with
// a 1 - cos rise from zero to the peak and the same fall at its end (MIL-F-8785C's discrete
// gust shape), so the wind has no jump.
struct Gust {
  double start = 0.0;              // [s] of flight time
  double rise = 0.5;               // [s] from zero to the peak, and from the peak back to zero
  double duration = 2.0;           // [s] in all, rise and fall included; >= 2 rise
  double peak = 2.0;               // [m/s]
  Vec3 direction = Vec3::UnitX();  // world frame; any length > 0

  // The gust's wind at flight time t [m/s].
  Vec3 At(double t) const;
  void Describe(Archive& a);  // [[wind.gusts]] (common/schema.h)
};

enum class Turbulence { kNone, kDryden };

struct WindParams {
  Vec3 mean = Vec3::Zero();  // [m/s] world frame
  std::vector<Gust> gusts;
  Turbulence turbulence = Turbulence::kNone;
  // The turbulence's standard deviations [m/s] in the wind frame: along the horizontal mean
  // wind (world x when there is none), across it (horizontal), vertical.
  Vec3 intensity = Vec3(1.0, 1.0, 0.5);
  // Dryden's filters scale with the airspeed (Taylor's frozen turbulence: the vehicle flies
  // through a field that stands still); below this airspeed [m/s], where that picture fails and
  // the filter would freeze, this value is used.
  double min_airspeed = 1.0;

  bool Enabled() const;
  void Describe(Archive& a);  // [wind] but its gusts (common/schema.h)
  // Throws std::invalid_argument naming the field.
  void Validate() const;
};

// MIL-F-8785C's low-altitude turbulence scale lengths [m] at height h [m] above the ground
// (h is clamped to 1-304.8 m, the model's range): L_w = h and L_u = L_v = h / (0.177 +
// 0.000823 h)^1.2, with h in feet inside.
Vec3 DrydenScaleLengths(double height);

// MIL-F-8785C's low-altitude turbulence intensities [m/s] (u, v, w) for the wind speed
// `wind_20ft` [m/s] at 20 ft (6.1 m) and a height [m] (clamped as above): sigma_w = 0.1 W20,
// sigma_u = sigma_v = sigma_w / (0.177 + 0.000823 h)^0.4, h in feet.
Vec3 DrydenIntensities(double wind_20ft, double height);

// Dryden turbulence: u (along the wind) with the first-order spectrum, v and w with the
// second-order ones, each a linear filter driven by white noise and advanced with its exact
// discretisation over each step (the transition matrix and the covariance it adds), so the
// statistics do not depend on the step. The filters' states are kept normalised to unit
// stationary variance, so a change of airspeed or height changes the correlation, never the
// intensity. Starts in its stationary distribution.
class DrydenTurbulence {
 public:
  DrydenTurbulence(const Vec3& intensity, std::uint64_t seed);
  // Advances by dt [s] at `airspeed` [m/s] (> 0) and `height` [m] above the ground; returns the
  // turbulence in the wind frame (u, v, w) [m/s].
  Vec3 Step(double dt, double airspeed, double height);
  Vec3 current() const { return current_; }

 private:
  Vec3 intensity_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  double u_ = 0.0;                               // normalised first-order state
  Eigen::Vector2d v_ = Eigen::Vector2d::Zero();  // normalised second-order states
  Eigen::Vector2d w_ = Eigen::Vector2d::Zero();
  Vec3 current_ = Vec3::Zero();
};

// The wind the vehicle meets: mean + gusts + turbulence, in the world frame.
class WindField {
 public:
  WindField(const WindParams& params, std::uint64_t seed);
  // Advances to flight time t [s] by dt [s] for a vehicle at `height` [m] above the ground with
  // velocity v_W [m/s]; returns the wind at the vehicle [m/s].
  Vec3 Step(double t, double dt, double height, const Vec3& v_W);
  Vec3 current() const { return current_; }

 private:
  WindParams params_;
  DrydenTurbulence turbulence_;
  Mat3 R_WT_ = Mat3::Identity();  // wind frame (u, v, w) to world
  Vec3 current_ = Vec3::Zero();
};

}  // namespace aerobox
