#pragma once
// MuJoCo's renderer (mjv_ scene, mjr_ context) drawing a PosedScene: the follower's layer solid
// with its contact points and forces, the twin's and the leader's layers as translucent ghosts of
// the arms (the bodies their joints move), in the window or into the offscreen buffer. Needs a
// current OpenGL context (gl_window.h) for its whole life.

#include <mujoco/mujoco.h>

#include <array>
#include <string>
#include <vector>

#include "teleop/view/image.h"
#include "teleop/view/posed_scene.h"

namespace teleop::view {

struct RenderSettings {
  /// Contact points and contact forces of the follower's layer (mjVIS_CONTACTPOINT, _FORCE).
  bool contacts = true;
  /// Side-by-side stereo (mjSTEREO_SIDEBYSIDE): the left eye's picture in the left half.
  bool stereo = false;
  bool shadows = true;
  bool reflections = true;
  /// Which layers are drawn (once posed), by Layer.
  std::array<bool, kLayerCount> layers{true, true, true};
  /// Ghost colours (r, g, b, alpha) of the twin and the leader's command.
  std::array<float, 4> twin_rgba{0.3f, 0.75f, 1.0f, 0.35f};
  std::array<float, 4> leader_rgba{1.0f, 0.65f, 0.2f, 0.3f};
};

/// A force drawn as an arrow from `from` [m] along `force` [N] (scaled by `m_per_n`), world frame.
struct ForceArrow {
  std::array<double, 3> from{};
  std::array<double, 3> force{};
};

class SceneRenderer {
 public:
  /// `offscreen_width` x `offscreen_height` (0: the model's own) is the offscreen buffer's size,
  /// `offscreen_samples` its multisampling (< 0: the model's own, MuJoCo's default 4; software
  /// OpenGL pays for each sample).
  SceneRenderer(PosedScene& scene, int offscreen_width = 0, int offscreen_height = 0, int offscreen_samples = -1);
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  RenderSettings& settings() { return settings_; }
  mjvCamera& camera() { return camera_; }
  mjvScene& scene() { return scene_; }
  const mjrContext& context() const { return context_; }

  /// The free camera looking at the model's centre from behind the robot's left shoulder
  /// (azimuth 60 deg, elevation -20 deg, MuJoCo's distance for the model's size), or from the
  /// angles the model chose itself (<visual><global azimuth elevation>: the hand's).
  void reset_camera();
  /// A camera of the model, by name. Throws std::runtime_error listing the model's cameras when
  /// it has none of that name.
  void use_model_camera(const std::string& name);
  /// The free camera with this azimuth and elevation [deg] and distance [m] (<= 0: keep).
  void orbit(double azimuth_deg, double elevation_deg, double distance_m);
  /// Where a view or render starts: the model's camera `name` when given, else the free camera
  /// turned to the given angles and distance (NaN angles and a distance <= 0 keep the default's).
  void start_camera(const std::string& name, double azimuth_deg, double elevation_deg, double distance_m);

  /// Arrows drawn with every frame from now on while contacts are shown (the external force at
  /// a flange).
  void set_arrows(std::vector<ForceArrow> arrows, double m_per_n);

  /// Draws into the window (false) or the offscreen buffer (true); the offscreen buffer's size.
  void use_offscreen(bool offscreen);
  mjrRect offscreen_rect() const;

  /// Builds the frame's geometry from the scene's posed layers, then draws it into `viewport` of
  /// the current buffer with `top_left` and `bottom_left` text (lines separated by '\n';
  /// each may be empty).
  void render(mjrRect viewport, const std::string& top_left, const std::string& bottom_left = "");
  /// The pixels of `viewport` of the current buffer (call before the window's buffers swap).
  Image read(mjrRect viewport) const;

 private:
  void compose();
  void add_ghost(Layer layer, const std::array<float, 4>& rgba);
  void add_arrows();

  PosedScene* posed_;
  RenderSettings settings_;
  mjvCamera camera_;
  mjvOption option_;
  mjvOption ghost_option_;
  mjvPerturb perturb_;
  mjvScene scene_;
  mjrContext context_;
  std::vector<ForceArrow> arrows_;
  double m_per_n_ = 0.005;
};

}  // namespace teleop::view
