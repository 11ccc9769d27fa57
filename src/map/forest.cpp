#include "map/forest.h"

#include <cmath>
#include <random>
#include <stdexcept>

#include "common/number_format.h"

namespace aerobox {
namespace {

// Millimetres: what a map file keeps, so that the map read back is this one.
double Mm(double x) { return std::round(x * 1000.0) / 1000.0; }

Aabb Rounded(const Vec3& min, const Vec3& max) { return {min.unaryExpr(&Mm), max.unaryExpr(&Mm)}; }

}  // namespace

void ForestParams::Describe(Archive& a) {
  a.Vector({"size", "m", "W x L x H: start to goal along x, across, height"}, &size, 2, 10000);
  a.Integer({"pillars", "", "how many pillars (Fast-Planner: 150 in 40 x 20 m)"}, &pillars, 0,
            1000000);
  a.Number({"width_min", "m", "a pillar's narrowest side"}, &width_min, 0.05, 100);
  a.Number({"width_max", "m", "a pillar's widest side"}, &width_max, 0.05, 100);
  a.Integer({"bars", "", "horizontal bars between the pillars"}, &bars, 0, 1000000);
  a.Number({"clear_ends", "m", "free ground at each end for the start and the goal"}, &clear_ends,
           0, 1000);
  a.Integer({"seed", "", "the forest's random seed"}, &seed, 0, 9007199254740991L);
}

void ForestParams::Validate() const {
  ValidateFields(*this, "forest");
  if (width_max < width_min) {
    throw std::invalid_argument("forest.width_max: " + FormatNumber(width_max) +
                                " m is below width_min " + FormatNumber(width_min) + " m");
  }
  if (!(2 * clear_ends + 2 < size.x())) {
    throw std::invalid_argument("forest.clear_ends: " + FormatNumber(clear_ends) +
                                " m at each end leaves no room for pillars in " +
                                FormatNumber(size.x()) + " m");
  }
}

Map MakeForest(const ForestParams& params) {
  params.Validate();
  Map map;
  map.name = "forest_" + std::to_string(params.seed);
  map.bounds = {Vec3::Zero(), params.size};
  std::mt19937_64 rng(static_cast<std::uint64_t>(params.seed));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double w = params.size.x(), l = params.size.y(), h = params.size.z();
  const auto add = [&map](const Aabb& extent, const Vec3& rgb) {
    map.boxes.push_back({extent, rgb, "block_" + std::to_string(map.boxes.size()), 0});
  };
  for (int i = 0; i < params.pillars; ++i) {
    const double side = params.width_min + (params.width_max - params.width_min) * unit(rng);
    const double x =
        params.clear_ends + 0.5 * side + (w - 2 * params.clear_ends - side) * unit(rng);
    const double y = l * unit(rng);
    const Vec3 c(x, y, 0.5 * h);
    const Vec3 half(0.5 * side, 0.5 * side, 0.5 * h);
    Aabb pillar = Rounded(c - half, c + half);
    pillar.min.y() = std::max(pillar.min.y(), 0.0);
    pillar.max.y() = std::min(pillar.max.y(), l);
    add(pillar, Vec3(0.45, 0.35, 0.25));
  }
  for (int i = 0; i < params.bars; ++i) {
    // 0.2 m thick, 2 to 4 m long, along x or y, between 1 m and 1 m below the top
    const double length = 2.0 + 2.0 * unit(rng);
    const bool along_x = unit(rng) < 0.5;
    const Vec3 c(params.clear_ends + (w - 2 * params.clear_ends) * unit(rng), l * unit(rng),
                 1.0 + std::max(0.0, h - 2.0) * unit(rng));
    const Vec3 half = along_x ? Vec3(0.5 * length, 0.1, 0.1) : Vec3(0.1, 0.5 * length, 0.1);
    add(Rounded((c - half).cwiseMax(map.bounds.min), (c + half).cwiseMin(map.bounds.max)),
        Vec3(0.3, 0.3, 0.35));
  }
  map.start = Vec3(1.0, Mm(0.5 * l), 1.0);
  map.goal = Vec3(Mm(w - 1.0), Mm(0.5 * l), 1.0);
  return map;
}

std::string MapJson(const Map& map) {
  const auto extents = [](const Aabb& b) {
    return "[" + FormatNumber(b.min.x()) + ", " + FormatNumber(b.max.x()) + ", " +
           FormatNumber(b.min.y()) + ", " + FormatNumber(b.max.y()) + ", " +
           FormatNumber(b.min.z()) + ", " + FormatNumber(b.max.z()) + "]";
  };
  const auto point = [](const Vec3& p) { return "[" + FormatVector(p, ", ") + "]"; };
  std::string text = "{\n  \"bounds\": {\"extents\": " + extents(map.bounds) + "},\n";
  text += "  \"blocks\": [";
  for (size_t i = 0; i < map.boxes.size(); ++i) {
    text += std::string(i == 0 ? "\n" : ",\n") +
            "    {\"extents\": " + extents(map.boxes[i].extent) +
            ", \"color\": " + point(map.boxes[i].rgb) + "}";
  }
  text += "\n  ]";
  if (map.start) text += ",\n  \"start\": " + point(*map.start);
  if (map.goal) text += ",\n  \"goal\": " + point(*map.goal);
  return text + "\n}\n";
}

}  // namespace aerobox
