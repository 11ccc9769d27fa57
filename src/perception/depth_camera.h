// An onboard depth camera: a pinhole camera on the vehicle that sees the map's boxes and the
// floor along its rays, so a box hidden behind another is not seen. Depth is ray cast exactly
// against the boxes (our maps are boxes; tests check it against MuJoCo's mj_ray), then a
// stereo-like error that grows with the square of the depth, and dropouts, are drawn from the
// camera's own seeded stream. Pure math: no renderer, no MuJoCo.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <utility>
#include <vector>

#include "common/schema.h"
#include "common/state.h"
#include "common/types.h"

namespace aerobox {

// The camera's own keys ([sensing] holds them beside the field of view, range and rate it shares
// with the other sensing kinds). Defaults: Fast-Planner's simulated camera at a quarter of its
// 640 x 480, a RealSense D435's depth field.
struct DepthCameraParams {
  int width = 160;                      // [px]
  int height = 120;                     // [px]
  double fov_horizontal = 1.5184;       // [rad] set through [sensing] fov
  double fov_vertical = 1.0123;         // [rad] set through [sensing] fov_vertical
  double range = 5.0;                   // [m] set through [sensing] range
  Vec3 mount_B = Vec3(0.05, 0.0, 0.0);  // [m] the optical centre on the body (FLU)
  double pitch = 0.0;                   // [rad] the optical axis above body x (nose up > 0)
  // [1/m] depth error sigma = noise * depth^2 (a D435 at 2 m: about 0.01); 0 keeps depth exact
  double noise = 0.0;
  double dropout = 0.0;  // fraction of pixels that return nothing, drawn per pixel and frame

  // width, height, mount, pitch, noise, dropout (common/schema.h); the rest is [sensing]'s
  void Describe(Archive& a);
  // Throws std::invalid_argument naming the key: a field of view of 180 degrees or more (a
  // pinhole cannot see it), a zero size, a range below 0.1 m.
  void Validate(const char* table) const;
};

// Where a pixel's ray ended.
enum : int { kNoReturn = -1, kFloor = -2, kDropped = -3 };

struct DepthImage {
  int width = 0, height = 0;
  Vec3 origin_W = Vec3::Zero();  // the optical centre [m]
  Mat3 R_WC = Mat3::Identity();  // camera axes in the world: x right, y down, z along the view
  // per pixel, rows from the top: the depth along the optical axis [m] (0: nothing within range,
  // or dropped), and what the ray hit (a box index, kFloor, kNoReturn or kDropped)
  std::vector<float> depth;
  std::vector<int> hit;
  // the unit rays through the pixels' centres in camera axes, rows from the top (the camera's,
  // shared by its frames)
  std::shared_ptr<const std::vector<Vec3>> rays_C;

  // The unit ray through pixel (u, v) in camera axes.
  const Vec3& RayC(int u, int v) const { return (*rays_C)[static_cast<size_t>(v * width + u)]; }
  // The world point a pixel's depth gives [m] (meaningless when its depth is 0).
  Vec3 PointW(int u, int v) const;
  double fx = 1.0, fy = 1.0;  // [px] focal lengths
};

class DepthCamera {
 public:
  DepthCamera(const DepthCameraParams& params, std::uint64_t seed);

  // One frame from the vehicle at `body` looking at `boxes` [m] and at the floor: the bottom of
  // `bounds` (no further than its sides reach: the flyable volume's floor).
  DepthImage Capture(const State& body, const std::vector<Aabb>& boxes, const Aabb& bounds);

  // The camera's pose for a vehicle at `body`.
  Vec3 OriginW(const State& body) const;
  Mat3 RotationWC(const State& body) const;
  const DepthCameraParams& params() const { return params_; }

 private:
  struct PixelRect {
    int u0, v0, u1, v1;  // inclusive
  };
  // The pixels whose rays may meet `box` (none: it lies wholly behind the camera).
  std::optional<PixelRect> Footprint(const DepthImage& image, const Aabb& box) const;
  // Depth along the optical axis from the rays' hits, then noise and dropouts.
  void AddNoise(DepthImage* image);

  DepthCameraParams params_;
  std::mt19937_64 rng_;
  std::shared_ptr<const std::vector<Vec3>> rays_C_;  // per pixel, in camera axes
  std::vector<Vec3> rays_;                           // this frame's rays in the world, per pixel
  std::vector<double> nearest_;  // [m] along each ray to what it hit (range: nothing)
  std::vector<std::pair<double, int>> candidates_;  // boxes within range: distance [m], index
};

}  // namespace aerobox
