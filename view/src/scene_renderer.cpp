#include "teleop/view/scene_renderer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace teleop::view {
namespace {

// room for the follower's scene, two ghosts of the arms and the contacts' decorations
constexpr int kMaxGeoms = 6000;
// MuJoCo's own free-camera angles (mjVisual.global defaults)
constexpr float kMujocoAzimuthDeg = 90;
constexpr float kMujocoElevationDeg = -45;

}  // namespace

SceneRenderer::SceneRenderer(PosedScene& scene, int offscreen_width, int offscreen_height, int offscreen_samples)
    : posed_(&scene) {
  mjModel* m = scene.model();
  if (offscreen_width > 0) m->vis.global.offwidth = offscreen_width;
  if (offscreen_height > 0) m->vis.global.offheight = offscreen_height;
  if (offscreen_samples >= 0) m->vis.quality.offsamples = offscreen_samples;
  mjv_defaultCamera(&camera_);
  mjv_defaultOption(&option_);
  mjv_defaultPerturb(&perturb_);
  mjv_defaultScene(&scene_);
  mjr_defaultContext(&context_);
  mjv_makeScene(m, &scene_, kMaxGeoms);
  mjr_makeContext(m, &context_, mjFONTSCALE_100);
  reset_camera();
}

SceneRenderer::~SceneRenderer() {
  mjr_freeContext(&context_);
  mjv_freeScene(&scene_);
}

void SceneRenderer::reset_camera() {
  const mjModel* m = posed_->model();
  mjv_defaultFreeCamera(m, &camera_);
  // a model that chose its own view (<visual><global azimuth elevation>: the hand's) keeps it
  if (m->vis.global.azimuth != kMujocoAzimuthDeg || m->vis.global.elevation != kMujocoElevationDeg) return;
  // MuJoCo's default looks along +y from 45 deg above: the wall of the stiff-wall scene edge-on.
  // From behind the robot's left shoulder, a little above, both arms and what they touch are seen
  camera_.azimuth = 60;
  camera_.elevation = -20;
}

void SceneRenderer::use_model_camera(const std::string& name) {
  const mjModel* m = posed_->model();
  const int id = mj_name2id(m, mjOBJ_CAMERA, name.c_str());
  if (id < 0) {
    std::string known;
    for (int c = 0; c < m->ncam; ++c) {
      const char* n = mj_id2name(m, mjOBJ_CAMERA, c);
      known += (known.empty() ? "" : ", ") + std::string(n != nullptr ? n : "(unnamed)");
    }
    throw std::runtime_error("model '" + posed_->spec().model_path + "' has no camera named '" + name +
                             "' (it has: " + (known.empty() ? "none" : known) + ")");
  }
  camera_.type = mjCAMERA_FIXED;
  camera_.fixedcamid = id;
}

void SceneRenderer::start_camera(const std::string& name, double azimuth_deg, double elevation_deg,
                                 double distance_m) {
  if (!name.empty()) {
    use_model_camera(name);
  } else if (!std::isnan(azimuth_deg) || !std::isnan(elevation_deg) || distance_m > 0) {
    orbit(std::isnan(azimuth_deg) ? camera_.azimuth : azimuth_deg,
          std::isnan(elevation_deg) ? camera_.elevation : elevation_deg, distance_m);
  }
}

void SceneRenderer::orbit(double azimuth_deg, double elevation_deg, double distance_m) {
  camera_.type = mjCAMERA_FREE;
  camera_.azimuth = azimuth_deg;
  camera_.elevation = elevation_deg;
  if (distance_m > 0) camera_.distance = distance_m;
}

void SceneRenderer::use_offscreen(bool offscreen) {
  mjr_setBuffer(offscreen ? mjFB_OFFSCREEN : mjFB_WINDOW, &context_);
}

mjrRect SceneRenderer::offscreen_rect() const { return {0, 0, context_.offWidth, context_.offHeight}; }

void SceneRenderer::compose() {
  const mjModel* m = posed_->model();
  const bool follower = settings_.layers[0] && posed_->posed(Layer::kFollower);
  option_.flags[mjVIS_CONTACTPOINT] = settings_.contacts && follower ? 1 : 0;
  option_.flags[mjVIS_CONTACTFORCE] = settings_.contacts && follower ? 1 : 0;
  // the world always; the follower's robot and objects once measured
  const int categories = mjCAT_STATIC | (follower ? mjCAT_DYNAMIC | mjCAT_DECOR : 0);
  mjv_updateScene(m, posed_->data(Layer::kFollower), &option_, &perturb_, &camera_, categories, &scene_);
  if (settings_.layers[1] && posed_->posed(Layer::kTwin)) add_ghost(Layer::kTwin, settings_.twin_rgba);
  if (settings_.layers[2] && posed_->posed(Layer::kLeader)) add_ghost(Layer::kLeader, settings_.leader_rgba);
  // the forces belong with the contacts: C hides both
  if (settings_.contacts) add_arrows();
  scene_.stereo = settings_.stereo ? mjSTEREO_SIDEBYSIDE : mjSTEREO_NONE;
  scene_.flags[mjRND_SHADOW] = settings_.shadows ? 1 : 0;
  scene_.flags[mjRND_REFLECTION] = settings_.reflections ? 1 : 0;
}

void SceneRenderer::add_ghost(Layer layer, const std::array<float, 4>& rgba) {
  const mjModel* m = posed_->model();
  ghost_option_ = option_;
  ghost_option_.flags[mjVIS_CONTACTPOINT] = 0;
  ghost_option_.flags[mjVIS_CONTACTFORCE] = 0;
  std::fill(std::begin(ghost_option_.sitegroup), std::end(ghost_option_.sitegroup), mjtByte{0});
  const int first = scene_.ngeom;
  mjv_addGeoms(m, posed_->data(layer), &ghost_option_, &perturb_, mjCAT_DYNAMIC, &scene_);
  // keep the arms' geoms only (an object's pose is the follower's, not the ghost's), tinted
  int kept = first;
  for (int i = first; i < scene_.ngeom; ++i) {
    mjvGeom g = scene_.geoms[i];
    if (g.objtype != mjOBJ_GEOM || !posed_->moved_by_arms(m->geom_bodyid[g.objid])) continue;
    for (int k = 0; k < 3; ++k) g.rgba[k] = 0.5f * g.rgba[k] + 0.5f * rgba[static_cast<size_t>(k)];
    g.rgba[3] = rgba[3];
    g.segid = -1;
    // a ghost where the follower is would flicker in and out of the solid arm (same depth): its
    // primitives a little larger (a mesh's size does not scale its drawing)
    if (g.type != mjGEOM_MESH) {
      for (float& size : g.size) size *= 1.02f;
    }
    scene_.geoms[kept++] = g;
  }
  scene_.ngeom = kept;
}

void SceneRenderer::set_arrows(std::vector<ForceArrow> arrows, double m_per_n) {
  arrows_ = std::move(arrows);
  m_per_n_ = m_per_n;
}

void SceneRenderer::add_arrows() {
  const mjModel* m = posed_->model();
  // as thick as MuJoCo draws contact forces, in the colour of its force arrows
  const double width = m->vis.scale.forcewidth * m->stat.meansize;
  for (const ForceArrow& a : arrows_) {
    const double length =
        std::sqrt(a.force[0] * a.force[0] + a.force[1] * a.force[1] + a.force[2] * a.force[2]) * m_per_n_;
    if (scene_.ngeom >= scene_.maxgeom || length < 1e-4 || !std::isfinite(length)) continue;
    mjvGeom* g = scene_.geoms + scene_.ngeom++;
    mjv_initGeom(g, mjGEOM_ARROW, nullptr, nullptr, nullptr, m->vis.rgba.contactforce);
    mjv_makeConnector(g, mjGEOM_ARROW, width, a.from[0], a.from[1], a.from[2], a.from[0] + a.force[0] * m_per_n_,
                      a.from[1] + a.force[1] * m_per_n_, a.from[2] + a.force[2] * m_per_n_);
    g->category = mjCAT_DECOR;
  }
}

void SceneRenderer::render(mjrRect viewport, const std::string& top_left, const std::string& bottom_left) {
  compose();
  mjr_render(viewport, &scene_, &context_);
  // the overlay's two columns: text before a tab on the left, after it on the right
  auto overlay = [&](int grid, const std::string& text) {
    if (text.empty()) return;
    std::string left, right;
    size_t start = 0;
    while (start <= text.size()) {
      const size_t end = std::min(text.find('\n', start), text.size());
      const std::string line = text.substr(start, end - start);
      const size_t tab = line.find('\t');
      left += (start == 0 ? "" : "\n") + line.substr(0, tab);
      right += (start == 0 ? "" : "\n") + (tab == std::string::npos ? std::string() : line.substr(tab + 1));
      start = end + 1;
    }
    mjr_overlay(mjFONT_NORMAL, grid, viewport, left.c_str(), right.c_str(), &context_);
  };
  overlay(mjGRID_TOPLEFT, top_left);
  overlay(mjGRID_BOTTOMLEFT, bottom_left);
}

Image SceneRenderer::read(mjrRect viewport) const {
  Image image(viewport.width, viewport.height);
  mjr_readPixels(image.rgb.data(), nullptr, viewport, &context_);
  image.flip_rows();
  return image;
}

}  // namespace teleop::view
