#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "render/offscreen_context.h"
#include "vehicle/model_names.h"

namespace aerobox {

CameraSpec ParseCamera(const std::string& name) {
  if (name == "chase") return {CameraKind::kChase, ""};
  if (name == "overview") return {CameraKind::kOverview, ""};
  if (name == "top") return {CameraKind::kTop, ""};
  throw std::invalid_argument("expected chase, overview or top, got '" + name + "'");
}
namespace {

constexpr int kOverlayGeoms = 6000;       // room in the scene for overlay geoms
constexpr int kMaxPolylinePoints = 1500;  // longer polylines are subsampled
constexpr size_t kMaxTreeEdges = 3000;    // a larger tree is drawn with every n-th edge

// Every n-th point so that at most kMaxPolylinePoints remain (the last one always).
std::vector<size_t> Subsample(size_t count) {
  std::vector<size_t> kept;
  const size_t step = std::max<size_t>(1, (count + kMaxPolylinePoints - 1) / kMaxPolylinePoints);
  for (size_t i = 0; i < count; i += step) kept.push_back(i);
  if (count > 0 && kept.back() != count - 1) kept.push_back(count - 1);
  return kept;
}

}  // namespace

struct Renderer::Impl {
  Simulation* sim = nullptr;
  RenderSettings settings;
  std::unique_ptr<OffscreenContext> context;
  mjvScene scene;
  mjrContext gl;
  mjvOption option;
  std::vector<unsigned char> buffer;
  // the chase camera's filtered state
  bool chase_started = false;
  Vec3 chase_lookat = Vec3::Zero();
  double chase_azimuth = 0.0;        // [deg]
  double chase_time = 0.0;           // simulation time of the last chase frame [s]
  double last_chase_distance = 0.0;  // [m], after pulling in
  int vehicle_body = -1;

  void AddLine(const Vec3& a, const Vec3& b, const float rgba[4], double width) {
    if (scene.ngeom >= scene.maxgeom) return;
    mjvGeom* geom = scene.geoms + scene.ngeom;
    mjv_initGeom(geom, mjGEOM_NONE, nullptr, nullptr, nullptr, rgba);
    mjv_makeConnector(geom, mjGEOM_LINE, width, a.x(), a.y(), a.z(), b.x(), b.y(), b.z());
    geom->category = mjCAT_DECOR;
    ++scene.ngeom;
  }

  void AddSphere(const Vec3& p, double radius, const float rgba[4]) {
    if (scene.ngeom >= scene.maxgeom) return;
    const mjtNum size[3] = {radius, radius, radius};
    const mjtNum pos[3] = {p.x(), p.y(), p.z()};
    mjv_initGeom(scene.geoms + scene.ngeom, mjGEOM_SPHERE, size, pos, nullptr, rgba);
    scene.geoms[scene.ngeom].category = mjCAT_DECOR;
    ++scene.ngeom;
  }

  void AddPolyline(const std::vector<Vec3>& points, const float rgba[4], double width) {
    const std::vector<size_t> kept = Subsample(points.size());
    for (size_t i = 1; i < kept.size(); ++i)
      AddLine(points[kept[i - 1]], points[kept[i]], rgba, width);
  }

  // The scenery; around the chase camera only what lies within `range` [m] of it (far
  // buildings are a few pixels each and cost as much to draw as near ones).
  void AddScenery(const CameraSpec& spec, double range) {
    const bool near_only = spec.kind == CameraKind::kChase;
    for (const SceneryBox& box : settings.scenery) {
      if (scene.ngeom >= scene.maxgeom) return;
      if (near_only) {
        const Vec3 outside = ((box.centre - box.half_size) - chase_lookat)
                                 .cwiseMax(chase_lookat - (box.centre + box.half_size))
                                 .cwiseMax(0.0);
        if (outside.norm() > range) continue;
      }
      const mjtNum size[3] = {box.half_size.x(), box.half_size.y(), box.half_size.z()};
      const mjtNum pos[3] = {box.centre.x(), box.centre.y(), box.centre.z()};
      const float rgba[4] = {static_cast<float>(box.rgb.x()), static_cast<float>(box.rgb.y()),
                             static_cast<float>(box.rgb.z()), 1.0f};
      mjv_initGeom(scene.geoms + scene.ngeom, mjGEOM_BOX, size, pos, nullptr, rgba);
      scene.geoms[scene.ngeom].category = mjCAT_STATIC;
      ++scene.ngeom;
    }
  }

  void AddOverlay(const Overlay& overlay) {
    const double scale = std::max(0.05, 0.01 * sim->model()->stat.extent);  // marker size [m]
    static const float kPath[4] = {0.95f, 0.75f, 0.1f, 1.0f};
    static const float kTrail[4] = {0.1f, 0.1f, 0.1f, 1.0f};
    // the start marker is see-through: the vehicle sits in it at the start
    static const float kStart[4] = {0.1f, 0.8f, 0.2f, 0.35f};
    static const float kGoal[4] = {0.9f, 0.15f, 0.1f, 0.9f};
    static const float kTree[4] = {0.35f, 0.55f, 0.35f, 0.6f};
    const size_t shown = std::min(overlay.tree_shown, overlay.tree.size());
    const size_t every = std::max<size_t>(1, (shown + kMaxTreeEdges - 1) / kMaxTreeEdges);
    for (size_t i = 0; i < shown; i += every) {
      AddLine(overlay.tree[i].first, overlay.tree[i].second, kTree, 1.0);
    }
    AddPolyline(overlay.path, kPath, 2.0);
    const std::vector<size_t> kept = Subsample(overlay.trajectory.size());
    double top = 1e-9;
    for (const double v : overlay.speeds) top = std::max(top, v);
    for (size_t i = 1; i < kept.size(); ++i) {
      const double v = kept[i] < overlay.speeds.size() ? overlay.speeds[kept[i]] / top : 0.0;
      const float rgba[4] = {static_cast<float>(v), 0.2f, static_cast<float>(1.0 - v), 1.0f};
      AddLine(overlay.trajectory[kept[i - 1]], overlay.trajectory[kept[i]], rgba, 3.0);
    }
    static const float kAbandoned[4] = {0.55f, 0.55f, 0.55f, 0.8f};
    for (const std::vector<Vec3>& path : overlay.abandoned) AddPolyline(path, kAbandoned, 2.0);
    AddPolyline(overlay.trail, kTrail, 2.0);
    if (overlay.wind_W && overlay.wind_W->norm() > 0.05) {
      static const float kWind[4] = {0.1f, 0.8f, 0.9f, 0.9f};
      constexpr double kMetresPerSpeed = 0.3;  // [m per m/s]
      if (scene.ngeom < scene.maxgeom) {
        const Vec3 a = overlay.wind_origin;
        const Vec3 b = a + kMetresPerSpeed * *overlay.wind_W;
        mjvGeom* geom = scene.geoms + scene.ngeom;
        mjv_initGeom(geom, mjGEOM_NONE, nullptr, nullptr, nullptr, kWind);
        mjv_makeConnector(geom, mjGEOM_ARROW, 0.02, a.x(), a.y(), a.z(), b.x(), b.y(), b.z());
        geom->category = mjCAT_DECOR;
        ++scene.ngeom;
      }
    }
    if (overlay.start) AddSphere(*overlay.start, scale, kStart);
    if (overlay.goal) AddSphere(*overlay.goal, scale, kGoal);
    for (const Vec3& goal : overlay.via) AddSphere(goal, scale, kGoal);
    // twice the other markers' size, in a colour no other line or marker has
    static const float kCollision[4] = {0.95f, 0.1f, 0.95f, 0.9f};
    if (overlay.collision) AddSphere(*overlay.collision, 2 * scale, kCollision);
    static const float kVehicle[4] = {0.05f, 0.05f, 0.05f, 0.7f};
    if (overlay.vehicle) AddSphere(*overlay.vehicle, 3 * scale, kVehicle);
    for (const Vec3& other : overlay.others) AddSphere(other, 3 * scale, kVehicle);
  }

  // The chase camera's distance: pulled in along the line of sight when a map box (geom
  // group 0) stands between the vehicle and the camera, so the view is never a wall's inside.
  double ChaseDistance(double azimuth_deg, double elevation_deg, double wanted) const {
    const double az = azimuth_deg * M_PI / 180.0;
    const double el = elevation_deg * M_PI / 180.0;
    // a free camera looks along (cos el cos az, cos el sin az, sin el) at `lookat`
    const mjtNum back[3] = {-std::cos(el) * std::cos(az), -std::cos(el) * std::sin(az),
                            -std::sin(el)};
    const mjtNum from[3] = {chase_lookat.x(), chase_lookat.y(), chase_lookat.z()};
    const mjtByte groups[mjNGROUP] = {1, 0, 0, 0, 0, 0};
    int geom = -1;
    const mjtNum hit =
        mj_ray(sim->model(), sim->data(), from, back, groups, 1, vehicle_body, &geom);
    constexpr double kGap = 0.05;     // [m] kept in front of the wall
    constexpr double kClosest = 0.2;  // [m] from the vehicle, at the nearest
    if (hit < 0 || hit >= wanted + kGap) return wanted;
    return std::max(kClosest, hit - kGap);
  }

  // What the chase camera follows: the vehicle, or the middle of several, their mean velocity,
  // and the radius around the middle that holds them all [m].
  struct Followed {
    Vec3 p_W, v_W;
    double radius;
  };
  Followed Follow() const {
    const int n = sim->vehicle_count();
    if (n == 1) {
      const State s = sim->VehicleState();
      return {s.p_W, s.v_W, 0.0};
    }
    Followed group{Vec3::Zero(), Vec3::Zero(), 0.0};
    for (int i = 0; i < n; ++i) {
      const State s = sim->vehicle(i).VehicleState();
      group.p_W += s.p_W / n;
      group.v_W += s.v_W / n;
    }
    for (int i = 0; i < n; ++i) {
      group.radius =
          std::max(group.radius, (sim->vehicle(i).VehicleState().p_W - group.p_W).norm());
    }
    return group;
  }

  mjvCamera Camera(const CameraSpec& spec) {
    const mjModel* m = sim->model();
    mjvCamera camera;
    mjv_defaultCamera(&camera);
    const auto fixed = [&](const char* name) {
      const int id = mj_name2id(m, mjOBJ_CAMERA, name);
      if (id < 0)
        throw std::invalid_argument(std::string("the scene has no camera '") + name + "'");
      camera.type = mjCAMERA_FIXED;
      camera.fixedcamid = id;
    };
    switch (spec.kind) {
      case CameraKind::kOverview:
        fixed(model_names::kOverviewCamera);
        break;
      case CameraKind::kNamed:
        fixed(spec.name.c_str());
        break;
      case CameraKind::kTop:
        camera.type = mjCAMERA_FREE;
        for (int k = 0; k < 3; ++k) camera.lookat[k] = m->stat.center[k];
        camera.elevation = -89.9;
        camera.azimuth = 90.0;
        camera.distance = 2.4 * m->stat.extent;
        break;
      case CameraKind::kChase: {
        // behind the direction of travel, above, following smoothly; several vehicles: their
        // middle, far enough back to hold them all
        const Followed state = Follow();
        const Vec3 v = state.v_W;
        double heading = chase_azimuth;
        if (v.head<2>().norm() > 0.3) heading = std::atan2(v.y(), v.x()) * 180.0 / M_PI;
        const double now = sim->time();
        if (!chase_started || now < chase_time) {
          chase_lookat = state.p_W;
          chase_azimuth = heading;
          chase_started = true;
        }
        // first-order filters on simulation time (0.15 s for the position, 0.8 s for the
        // heading), so the camera moves the same at any frame rate
        const double dt = now - chase_time;
        chase_time = now;
        const double follow = 1.0 - std::exp(-dt / 0.15);
        const double turn = 1.0 - std::exp(-dt / 0.8);
        chase_azimuth += turn * std::remainder(heading - chase_azimuth, 360.0);
        chase_lookat += follow * (state.p_W - chase_lookat);
        camera.type = mjCAMERA_FREE;
        for (int k = 0; k < 3; ++k) camera.lookat[k] = chase_lookat[k];
        camera.azimuth = chase_azimuth;
        camera.elevation = -22.0;
        camera.distance = ChaseDistance(camera.azimuth, camera.elevation,
                                        std::max(settings.chase_distance, 2.6 * state.radius));
        last_chase_distance = camera.distance;
        break;
      }
    }
    return camera;
  }
};

Renderer::Renderer(Simulation* sim, const RenderSettings& settings)
    : impl_(std::make_unique<Impl>()) {
  mjModel* m = sim->mutable_model();
  const int buffer_width = m->vis.global.offwidth;
  const int buffer_height = m->vis.global.offheight;
  if (settings.width < 16 || settings.height < 16 || settings.width > buffer_width ||
      settings.height > buffer_height) {
    throw std::invalid_argument(
        "render size " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
        " does not fit the scene's off-screen buffer " + std::to_string(buffer_width) + "x" +
        std::to_string(buffer_height) + " (minimum 16x16)");
  }
  impl_->sim = sim;
  impl_->settings = settings;
  impl_->vehicle_body = mj_name2id(m, mjOBJ_BODY, model_names::kBody);
  impl_->context = std::make_unique<OffscreenContext>(settings.width, settings.height);
  // multisampling, the shadow map's size and the off-screen buffer's are read from the model
  // when the GL context is made, and only then: they are set for this renderer and put back
  // afterwards, so the model (shared with the physics and other renderers) is left as it was.
  // The fast preset draws no shadows, so it allocates no 4096^2 shadow map either; the
  // off-screen buffer only needs the image's size, and a smaller one is quicker to allocate.
  const mjVisual original = m->vis;
  m->vis.quality.offsamples = settings.quality == Quality::kPretty ? 4 : 0;
  if (settings.quality == Quality::kFast) m->vis.quality.shadowsize = 1;
  m->vis.global.offwidth = settings.width;
  m->vis.global.offheight = settings.height;
  mjv_defaultScene(&impl_->scene);
  mjv_defaultOption(&impl_->option);
  mjr_defaultContext(&impl_->gl);
  mjv_makeScene(m, &impl_->scene,
                m->ngeom + kOverlayGeoms + static_cast<int>(kMaxTreeEdges) +
                    static_cast<int>(settings.scenery.size()));
  mjr_makeContext(m, &impl_->gl, mjFONTSCALE_150);
  m->vis = original;
  mjr_setBuffer(mjFB_OFFSCREEN, &impl_->gl);
  const bool pretty = settings.quality == Quality::kPretty;
  impl_->scene.flags[mjRND_SHADOW] = pretty;
  impl_->scene.flags[mjRND_REFLECTION] = pretty;
  impl_->buffer.resize(static_cast<size_t>(settings.width) * settings.height * 3);
}

Renderer::~Renderer() {
  // the GL objects belong to the context, whichever thread made them; without it current,
  // nothing can be freed here, and OSMesa frees them with the context
  bool current = true;
  try {
    impl_->context->MakeCurrent();
  } catch (const std::runtime_error&) {
    current = false;
  }
  if (current) mjr_freeContext(&impl_->gl);
  mjv_freeScene(&impl_->scene);
}

void Renderer::CompileShaders() {
  const Vec3 p = impl_->sim->VehicleState().p_W;
  const Vec3 step(0.5, 0.5, 0.5);
  Overlay every;
  every.path = every.trajectory = every.trail = {p, p + step};
  every.speeds = {0.0, 1.0};
  every.abandoned = {every.path};
  every.start = p;
  every.goal = p + step;
  every.via = {p - step};
  every.collision = p;
  every.vehicle = p;
  every.text = "t 0.0 s";
  every.legend = "legend";
  every.tree = {{p, p + step}};
  every.tree_shown = 1;
  every.top_inset = true;
  every.wind_W = Vec3(1, 0, 0);
  every.wind_origin = p;
  Image scratch;
  Render({CameraKind::kOverview, ""}, every, &scratch);  // the chase camera keeps its state
}

void Renderer::ReleaseFromThread() { OffscreenContext::ReleaseCurrent(); }

int Renderer::width() const { return impl_->settings.width; }
double Renderer::last_chase_distance() const { return impl_->last_chase_distance; }
int Renderer::height() const { return impl_->settings.height; }

void Renderer::Render(const CameraSpec& spec, const Overlay& overlay, Image* out) {
  Impl& r = *impl_;
  r.context->MakeCurrent();
  mjvCamera camera = r.Camera(spec);
  mjv_updateScene(r.sim->model(), r.sim->mutable_data(), &r.option, nullptr, &camera, mjCAT_ALL,
                  &r.scene);
  r.AddScenery(spec, r.settings.chase_scenery_range);
  r.AddOverlay(overlay);
  const mjrRect viewport = {0, 0, r.settings.width, r.settings.height};
  mjr_render(viewport, &r.scene, &r.gl);
  if (overlay.top_inset) {
    // the same scene from above, in the top-right corner (MuJoCo's rectangles start at the
    // bottom left)
    mjvCamera top = r.Camera({CameraKind::kTop, ""});
    mjv_updateScene(r.sim->model(), r.sim->mutable_data(), &r.option, nullptr, &top, mjCAT_ALL,
                    &r.scene);
    r.AddScenery({CameraKind::kTop, ""}, r.settings.chase_scenery_range);
    r.AddOverlay(overlay);
    const int w = r.settings.width / 3;
    const int h = r.settings.height / 3;
    constexpr int kMargin = 4;                                   // [pixels]
    const int below_text = overlay.text.empty() ? kMargin : 30;  // under the top line of text
    const mjrRect inset = {r.settings.width - w - kMargin, r.settings.height - h - below_text, w,
                           h};
    mjr_render(inset, &r.scene, &r.gl);
  }
  if (!overlay.legend.empty()) {
    mjr_overlay(mjFONT_NORMAL, mjGRID_BOTTOMLEFT, viewport, overlay.legend.c_str(), nullptr, &r.gl);
  }
  if (!overlay.text.empty()) {
    mjr_overlay(mjFONT_NORMAL, mjGRID_TOPLEFT, viewport, overlay.text.c_str(), nullptr, &r.gl);
  }
  mjr_readPixels(r.buffer.data(), nullptr, viewport, &r.gl);
  // MuJoCo reads rows bottom-up; images are top-down
  out->width = r.settings.width;
  out->height = r.settings.height;
  out->rgb.resize(r.buffer.size());
  const size_t row = static_cast<size_t>(r.settings.width) * 3;
  for (int y = 0; y < r.settings.height; ++y) {
    std::memcpy(&out->rgb[y * row], &r.buffer[(r.settings.height - 1 - y) * row], row);
  }
}

}  // namespace aerobox
