#include "perception/depth_camera.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "common/number_format.h"
#include "geometry/ray_cast.h"

namespace aerobox {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;

// Camera axes (x right, y down, z along the view, as OpenCV's) in the body (FLU), the optical
// axis raised by `pitch`.
Mat3 RotationBC(double pitch) {
  Mat3 level;
  level.col(0) = Vec3(0, -1, 0);
  level.col(1) = Vec3(0, 0, -1);
  level.col(2) = Vec3(1, 0, 0);
  return Eigen::AngleAxisd(-pitch, Vec3::UnitY()).toRotationMatrix() * level;
}

// Where a ray from `o` along `d` meets the floor of `bounds` (+infinity when it never does, or
// beyond the bounds' sides).
double RayToFloor(const Vec3& o, const Vec3& d, const Aabb& bounds) {
  if (d.z() >= 0.0 || o.z() < bounds.min.z()) return kInf;
  const double t = (bounds.min.z() - o.z()) / d.z();
  const Vec3 p = o + t * d;
  if (p.x() < bounds.min.x() || p.x() > bounds.max.x() || p.y() < bounds.min.y() ||
      p.y() > bounds.max.y()) {
    return kInf;
  }
  return t;
}

}  // namespace

void DepthCameraParams::Describe(Archive& a) {
  a.Integer({"width", "px", "depth image columns (kind \"depth\")"}, &width, 1, 4096);
  a.Integer({"height", "px", "depth image rows (kind \"depth\")"}, &height, 1, 4096);
  a.Vector({"mount", "m", "the depth camera's optical centre on the body (x forward, y left)"},
           &mount_B, -1, 1);
  a.Degrees({"pitch", "deg", "the depth camera's optical axis above body x"}, &pitch, -90, 90);
  a.Number({"noise", "1/m", "depth error sigma per depth squared (a D435: about 0.01)"}, &noise, 0,
           1);
  a.Number({"dropout", "", "fraction of depth pixels that return nothing"}, &dropout, 0, 0.99);
}

void DepthCameraParams::Validate(const char* table) const {
  ValidateFields(*this, table);
  const std::string t = table;
  for (const auto& [name, value] :
       {std::pair<const char*, double>{"fov", fov_horizontal}, {"fov_vertical", fov_vertical}}) {
    if (!(value > 0.0 && value < kPi - 1e-9)) {
      throw std::invalid_argument(t + "." + name + ": a depth camera sees less than 180 deg (got " +
                                  FormatNumber(std::round(value * 1800.0 / kPi) / 10.0) + " deg)");
    }
  }
  if (!(range >= 0.1)) {
    throw std::invalid_argument(t + ".range: a depth camera needs at least 0.1 m (got " +
                                FormatNumber(range) + " m)");
  }
}

Vec3 DepthImage::PointW(int u, int v) const {
  const Vec3 ray = RayC(u, v);
  return origin_W + R_WC * (ray / ray.z() * depth[static_cast<size_t>(v * width + u)]);
}

DepthCamera::DepthCamera(const DepthCameraParams& params, std::uint64_t seed)
    : params_(params), rng_(seed) {
  const double fx = 0.5 * params_.width / std::tan(0.5 * params_.fov_horizontal);
  const double fy = 0.5 * params_.height / std::tan(0.5 * params_.fov_vertical);
  auto rays = std::make_shared<std::vector<Vec3>>();
  for (int v = 0; v < params_.height; ++v) {
    for (int u = 0; u < params_.width; ++u) {
      rays->push_back(
          Vec3((u + 0.5 - 0.5 * params_.width) / fx, (v + 0.5 - 0.5 * params_.height) / fy, 1.0)
              .normalized());
    }
  }
  rays_C_ = std::move(rays);
}

Vec3 DepthCamera::OriginW(const State& body) const {
  return body.p_W + body.q_WB * params_.mount_B;
}

Mat3 DepthCamera::RotationWC(const State& body) const {
  return body.q_WB.toRotationMatrix() * RotationBC(params_.pitch);
}

DepthImage DepthCamera::Capture(const State& body, const std::vector<Aabb>& boxes,
                                const Aabb& bounds) {
  DepthImage image;
  image.width = params_.width;
  image.height = params_.height;
  image.origin_W = OriginW(body);
  image.R_WC = RotationWC(body);
  image.fx = 0.5 * params_.width / std::tan(0.5 * params_.fov_horizontal);
  image.fy = 0.5 * params_.height / std::tan(0.5 * params_.fov_vertical);
  image.rays_C = rays_C_;
  const size_t pixels = static_cast<size_t>(params_.width) * static_cast<size_t>(params_.height);
  image.depth.assign(pixels, 0.0f);
  image.hit.assign(pixels, kNoReturn);
  // per pixel: its ray in the world and the nearest surface on it, the floor first
  const Vec3& o = image.origin_W;
  rays_.resize(pixels);
  nearest_.resize(pixels);
  for (int v = 0; v < params_.height; ++v) {
    for (int u = 0; u < params_.width; ++u) {
      const size_t k = static_cast<size_t>(v * params_.width + u);
      rays_[k] = image.R_WC * image.RayC(u, v);
      nearest_[k] = std::min(params_.range, RayToFloor(o, rays_[k], bounds));
      if (nearest_[k] < params_.range) image.hit[k] = kFloor;
    }
  }
  // then every box within range, nearest first, over the pixels its projection covers: a pixel
  // whose surface is nearer than the box cannot see it; of equal hits, the first box in the
  // map's order wins (the floor wins over a box)
  candidates_.clear();
  for (size_t i = 0; i < boxes.size(); ++i) {
    const double distance = (o.cwiseMax(boxes[i].min).cwiseMin(boxes[i].max) - o).norm();
    if (distance <= params_.range) candidates_.push_back({distance, static_cast<int>(i)});
  }
  std::sort(candidates_.begin(), candidates_.end());
  for (const auto& [distance, i] : candidates_) {
    const Aabb& box = boxes[static_cast<size_t>(i)];
    const std::optional<PixelRect> rect = Footprint(image, box);
    if (!rect) continue;
    for (int v = rect->v0; v <= rect->v1; ++v) {
      for (int u = rect->u0; u <= rect->u1; ++u) {
        const size_t k = static_cast<size_t>(v * params_.width + u);
        if (nearest_[k] < distance) continue;
        const double t = RayToBox(o, rays_[k], box);
        if (t < nearest_[k] || (t == nearest_[k] && image.hit[k] >= 0 && i < image.hit[k])) {
          nearest_[k] = t;
          image.hit[k] = i;
        }
      }
    }
  }
  AddNoise(&image);
  return image;
}

std::optional<DepthCamera::PixelRect> DepthCamera::Footprint(const DepthImage& image,
                                                             const Aabb& box) const {
  // a box wholly in front of the camera projects inside the rectangle of its corners' pixels;
  // one that reaches behind the camera may cover any pixel; one wholly behind it, none
  double u_lo = kInf, u_hi = -kInf, v_lo = kInf, v_hi = -kInf;
  int behind = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 c((corner & 1) ? box.max.x() : box.min.x(), (corner & 2) ? box.max.y() : box.min.y(),
                 (corner & 4) ? box.max.z() : box.min.z());
    const Vec3 p = image.R_WC.transpose() * (c - image.origin_W);
    if (p.z() <= 1e-9) {
      ++behind;
      continue;
    }
    // the pixel whose centre's ray passes through p: u + 0.5 - width / 2 = fx x / z
    const double u = image.fx * p.x() / p.z() + 0.5 * image.width - 0.5;
    const double v = image.fy * p.y() / p.z() + 0.5 * image.height - 0.5;
    u_lo = std::min(u_lo, u), u_hi = std::max(u_hi, u);
    v_lo = std::min(v_lo, v), v_hi = std::max(v_hi, v);
  }
  if (behind == 8) return std::nullopt;
  PixelRect rect{0, 0, image.width - 1, image.height - 1};
  if (behind > 0) return rect;
  // a pixel's centre ray meets the box only when it lies within the corners' hull; one pixel
  // more on each side against rounding
  rect.u0 = static_cast<int>(std::max(0.0, std::floor(u_lo) - 1.0));
  rect.v0 = static_cast<int>(std::max(0.0, std::floor(v_lo) - 1.0));
  rect.u1 = static_cast<int>(std::min(image.width - 1.0, std::ceil(u_hi) + 1.0));
  rect.v1 = static_cast<int>(std::min(image.height - 1.0, std::ceil(v_hi) + 1.0));
  if (rect.u0 > rect.u1 || rect.v0 > rect.v1) return std::nullopt;
  return rect;
}

void DepthCamera::AddNoise(DepthImage* image) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  // drawn for every returning pixel, so that a frame's draws do not depend on the noise (an
  // exact camera draws nothing: its images are the same either way)
  const bool draws = params_.noise > 0.0 || params_.dropout > 0.0;
  for (int v = 0; v < image->height; ++v) {
    for (int u = 0; u < image->width; ++u) {
      const size_t k = static_cast<size_t>(v * image->width + u);
      if (image->hit[k] == kNoReturn) continue;
      const double cos_axis = image->RayC(u, v).z();
      double depth = nearest_[k] * cos_axis;
      const double error = draws ? normal(rng_) : 0.0, drop = draws ? uniform(rng_) : 1.0;
      if (drop < params_.dropout) {
        image->hit[k] = kDropped;
        continue;
      }
      depth += params_.noise * depth * depth * error;
      if (!(depth > 0.0) || depth / cos_axis > params_.range) {
        image->hit[k] = kNoReturn;
        continue;
      }
      image->depth[k] = static_cast<float>(depth);
    }
  }
}

}  // namespace aerobox
