#include "perception/depth_camera.h"

#include <algorithm>
#include <cmath>
#include <limits>
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

Vec3 DepthImage::RayC(int u, int v) const {
  const Vec3 ray((u + 0.5 - 0.5 * width) / fx, (v + 0.5 - 0.5 * height) / fy, 1.0);
  return ray.normalized();
}

Vec3 DepthImage::PointW(int u, int v) const {
  const Vec3 ray = RayC(u, v);
  return origin_W + R_WC * (ray / ray.z() * depth[static_cast<size_t>(v * width + u)]);
}

DepthCamera::DepthCamera(const DepthCameraParams& params, std::uint64_t seed)
    : params_(params), rng_(seed) {}

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
  const size_t pixels = static_cast<size_t>(params_.width) * static_cast<size_t>(params_.height);
  image.depth.assign(pixels, 0.0f);
  image.hit.assign(pixels, kNoReturn);
  // only the boxes within range can be seen
  const Vec3& o = image.origin_W;
  near_.clear();
  for (size_t i = 0; i < boxes.size(); ++i) {
    if ((o.cwiseMax(boxes[i].min).cwiseMin(boxes[i].max) - o).norm() <= params_.range) {
      near_.push_back(i);
    }
  }
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int v = 0; v < params_.height; ++v) {
    for (int u = 0; u < params_.width; ++u) {
      const Vec3 ray_C = image.RayC(u, v);
      const Vec3 d = image.R_WC * ray_C;
      double nearest = std::min(params_.range, RayToFloor(o, d, bounds));
      int hit = nearest < params_.range ? kFloor : kNoReturn;
      for (const size_t i : near_) {
        const double t = RayToBox(o, d, boxes[i]);
        if (t < nearest) {
          nearest = t;
          hit = static_cast<int>(i);
        }
      }
      if (hit == kNoReturn) continue;
      const size_t k =
          static_cast<size_t>(v) * static_cast<size_t>(params_.width) + static_cast<size_t>(u);
      double depth = nearest * ray_C.z();
      // drawn for every returning pixel, so that a frame's draws do not depend on the noise
      const double error = normal(rng_), drop = uniform(rng_);
      if (drop < params_.dropout) {
        image.hit[k] = kDropped;
        continue;
      }
      depth += params_.noise * depth * depth * error;
      if (!(depth > 0.0) || depth / ray_C.z() > params_.range) continue;
      image.depth[k] = static_cast<float>(depth);
      image.hit[k] = hit;
    }
  }
  return image;
}

}  // namespace aerobox
