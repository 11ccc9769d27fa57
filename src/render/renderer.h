// Off-screen rendering of a simulation with MuJoCo's mjv_/mjr_ API on OSMesa: cameras (chase,
// overview, top, or one named in the scene), overlays drawn into the scene (path, trajectory
// coloured by speed, flown trail, start and goal, a text line), RGB images top-down.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/types.h"
#include "render/image.h"
#include "sim/simulation.h"

namespace aerobox {

enum class Quality {
  kFast,    // no shadows, reflections or multisampling
  kPretty,  // shadows, reflections, 4x multisampling
};

enum class CameraKind { kChase, kOverview, kTop, kNamed };

struct CameraSpec {
  CameraKind kind = CameraKind::kChase;
  std::string name;  // for kNamed: a camera of the scene
};

// The camera a user names: "chase", "overview" or "top"; throws std::invalid_argument
// ("expected chase, overview or top, got 'x'") for any other name.
CameraSpec ParseCamera(const std::string& name);

// A box drawn in every frame that is not part of the simulated scene: the far buildings of a
// city flight, left out of MuJoCo's model to keep its steps cheap (SceneOptions::keep_boxes).
struct SceneryBox {
  Vec3 centre;     // [m, world]
  Vec3 half_size;  // [m]
  Vec3 rgb;        // each in [0, 1]
};

struct RenderSettings {
  RenderSettings() = default;
  RenderSettings(int width_px, int height_px, Quality preset)
      : width(width_px), height(height_px), quality(preset) {}

  int width = 640;  // [pixels], at most the scene's off-screen buffer
  int height = 480;
  Quality quality = Quality::kFast;
  std::vector<SceneryBox> scenery;     // drawn in every frame, under the overlays
  double chase_distance = 1.4;         // [m] from the chase camera to the vehicle
  double chase_scenery_range = 300.0;  // [m] the chase camera draws scenery this near
};

struct Overlay {
  std::vector<Vec3> path;        // the planner's polyline [m]
  std::vector<Vec3> trajectory;  // samples of the trajectory [m] ...
  std::vector<double> speeds;    // ... and the speed at each [m/s] (colour: blue slow, red fast)
  std::vector<Vec3> trail;       // where the vehicle has been [m]
  std::vector<std::vector<Vec3>> abandoned;  // paths given up when replanning [m], in grey
  std::optional<Vec3> start;
  std::optional<Vec3> goal;
  std::vector<Vec3> via;          // a mission's goals before the last, drawn as the goal is
  std::optional<Vec3> collision;  // where the flight hit a box [m]: a large magenta marker
  // the vehicle [m], marked for a camera that sees the whole map, from which a 10 cm vehicle
  // is a pixel or two (the overview and top cameras)
  std::optional<Vec3> vehicle;
  std::vector<Vec3> others;  // [m] the other vehicles of a world of several, marked alike
  std::string text;          // top-left text, lines separated by '\n'
  // the planner's tree, as (node, parent) edges in the order they were added; the first
  // `tree_shown` are drawn (at most kMaxTreeEdges of them, evenly chosen)
  std::vector<std::pair<Vec3, Vec3>> tree;
  size_t tree_shown = 0;
  // a top-down view of the whole map in the top-right corner (a third of the picture's size),
  // for when the main view hides the route
  bool top_inset = false;
  // bottom-left text, lines separated by '\n' (what the lines' colours mean)
  std::string legend;
  // the wind [m/s] as a cyan arrow from `wind_origin` [m], 0.3 m long per m/s (none when
  // empty)
  std::optional<Vec3> wind_W;
  Vec3 wind_origin = Vec3::Zero();
};

class Renderer {
 public:
  // Throws std::invalid_argument when the size exceeds the scene's off-screen buffer
  // (<visual><global offwidth offheight>): MuJoCo would clip the picture without a word.
  Renderer(Simulation* sim, const RenderSettings& settings);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Renders the simulation's current state. The chase camera follows the vehicle smoothly
  // (its position and heading are filtered from frame to frame). Throws std::invalid_argument
  // for a named camera the scene does not have.
  void Render(const CameraSpec& camera, const Overlay& overlay, Image* out);

  // Draws, and throws away, one frame with every kind of overlay, leaving the chase camera's
  // state as it was: a CPU renderer (llvmpipe) compiles its shaders at the first frame that
  // needs them (0.45-0.6 s in all), which then happens here, where the caller chooses (the
  // scene thread, while the planner works), not at the flight's first frame.
  void CompileShaders();

  // Lets another thread render from now on: the constructor leaves the GL context current in
  // the thread that made it, and each Render() makes it current in its own thread.
  void ReleaseFromThread();

  int width() const;
  int height() const;
  // The chase camera's distance to the vehicle in the last chase frame [m]: the settings', or
  // less where a box stood in the way.
  double last_chase_distance() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace aerobox
