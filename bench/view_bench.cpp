// Frames per second of the 3D view (docs/view.md): MuJoCo's renderer drawing the follower solid
// (with its contacts, from a forward dynamics of the measured state) and the twin as a ghost,
// into a window as `teleop view` does (pose, render, swap) and into the offscreen buffer as
// `teleop render` does (pose, render, read the pixels back; no encoding), for the one-arm scene
// (config/nodes/follower.yaml: scene_wall.xml) and the two-arm one (follower_box_task.yaml:
// scene_box_shelf.xml). Needs a display: under Xvfb it measures Mesa's software OpenGL,
//   xvfb-run -a -s "-screen 0 1920x1080x24" build/default/bin/teleop_view_bench
#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "teleop/view/gl_window.h"
#include "teleop/view/posed_scene.h"
#include "teleop/view/scene_renderer.h"
#include "teleop/view/view_model.h"

namespace {

using namespace teleop::view;

// the follower's arms swinging about their keyframe, the twin's a little ahead
void pose(PosedScene& scene, const std::vector<std::vector<double>>& home, int frame) {
  for (size_t a = 0; a < scene.arm_count(); ++a) {
    std::vector<double> q = home[a];
    q[0] += 0.3 * std::sin(0.05 * frame);
    scene.set_joints(Layer::kFollower, a, q.data(), q.size());
    q[0] += 0.2;
    scene.set_joints(Layer::kTwin, a, q.data(), q.size());
  }
  scene.update();
}

std::vector<std::vector<double>> home_pose(PosedScene& scene) {
  std::vector<std::vector<double>> home;
  const mjModel* m = scene.model();
  for (size_t a = 0; a < scene.arm_count(); ++a) {
    const std::string prefix = scene.arm(a).joint_prefix;
    std::vector<double> q;
    for (int u = 0; u < m->nu && q.size() < scene.joint_count(a); ++u) {
      const int j = m->actuator_trnid[2 * u];
      const char* name = mj_id2name(m, mjOBJ_JOINT, j);
      if (m->jnt_type[j] != mjJNT_HINGE || name == nullptr || std::string(name).rfind(prefix, 0) != 0) continue;
      q.push_back(scene.data(Layer::kFollower)->qpos[m->jnt_qposadr[j]]);
    }
    home.push_back(q);
  }
  return home;
}

double measure(PosedScene& scene, bool offscreen, int frames, int width, int height, bool shadows, int samples) {
  GlWindow window("teleop_view_bench", offscreen ? 64 : width, offscreen ? 64 : height, !offscreen);
  SceneRenderer renderer(scene, width, height, samples);
  renderer.settings().shadows = shadows;
  renderer.use_offscreen(offscreen);
  const std::vector<std::vector<double>> home = home_pose(scene);
  const mjrRect rect = offscreen ? mjrRect{0, 0, width, height} : window.framebuffer();
  double seconds = 0;
  for (int k = -5; k < frames; ++k) {  // five frames to warm up
    const auto start = std::chrono::steady_clock::now();
    pose(scene, home, k);
    renderer.render(rect, "bench\t0 fps");
    if (offscreen) {
      const Image image = renderer.read(rect);
      (void)image;
    } else {
      window.swap_buffers();
      window.poll_events();
    }
    if (k >= 0) seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return frames / seconds;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"teleop_view_bench: frames per second of teleop view and teleop render"};
  int frames = 100;
  int width = 1280;
  int height = 720;
  bool shadows = true;
  int samples = -1;
  app.add_option("-n,--frames", frames, "frames per measurement (default 100)")->check(CLI::Range(1, 100000));
  app.add_option("--width", width, "picture width (default 1280)")->check(CLI::Range(64, 4096));
  app.add_option("--height", height, "picture height (default 720)")->check(CLI::Range(64, 4096));
  app.add_flag("--no-shadows{false}", shadows, "without shadows");
  app.add_option("--samples", samples, "multisamples of the offscreen buffer (default: the model's, 4)")
      ->check(CLI::Range(0, 16));
  CLI11_PARSE(app, argc, argv);
  try {
    std::printf("%-34s %-10s %10s %10s\n", "scene", "target", "fps", "ms/frame");
    for (const char* node : {"follower.yaml", "follower_box_task.yaml"}) {
      PosedScene scene(read_view_model(std::string(TELEOP_SOURCE_DIR) + "/config/nodes/" + node));
      for (bool offscreen : {false, true}) {
        const double fps = measure(scene, offscreen, frames, width, height, shadows, samples);
        std::printf("%-34s %-10s %10.1f %10.1f\n",
                    (std::string(node) + " (" + std::to_string(scene.arm_count()) + " arm" +
                     (scene.arm_count() > 1 ? "s)" : ")"))
                        .c_str(),
                    offscreen ? "offscreen" : "window", fps, 1000.0 / fps);
        std::fflush(stdout);
      }
    }
    std::printf("%dx%d, %d frames each, shadows %s, offscreen multisamples %s\n", width, height, frames,
                shadows ? "on" : "off", samples < 0 ? "4 (the model's)" : std::to_string(samples).c_str());
  } catch (const DisplayError& e) {
    std::fprintf(stderr, "teleop_view_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
