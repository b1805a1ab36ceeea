#include "teleop/view/render_run.h"

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>

#include "teleop/common/data_paths.h"
#include "teleop/runtime/shutdown_signal.h"
#include "teleop/view/gl_window.h"
#include "teleop/view/posed_scene.h"
#include "teleop/view/run_playback.h"
#include "teleop/view/scene_renderer.h"
#include "teleop/view/video_writer.h"
#include "teleop/view/view_model.h"

namespace teleop::view {

namespace fs = std::filesystem;

namespace {

bool is_video(const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  return ext == ".mp4" || ext == ".mkv" || ext == ".mov" || ext == ".webm";
}

// "mmt/lan" for <report dir>/mmt/lan: what the overlay names the run by
std::string run_label(const std::string& run_dir) {
  const fs::path p = fs::absolute(run_dir).lexically_normal();
  const fs::path dir = p.filename().empty() ? p.parent_path() : p;
  return (dir.parent_path().filename() / dir.filename()).string();
}

}  // namespace

std::string default_scene_config(const std::string& run_dir) {
  std::ifstream in(fs::path(run_dir) / "follower.csv");
  std::string header;
  std::getline(in, header);
  const bool two_arms = header.find(",left_q_0") != std::string::npos;
  return shipped_node_config(two_arms ? "follower_box_task" : "follower");
}

RenderResult render_run(const RenderOptions& options, FILE* log) {
  const auto wall_start = std::chrono::steady_clock::now();
  RenderResult result;
  result.config_path = options.config_path.empty() ? default_scene_config(options.run_dir) : options.config_path;
  PosedScene scene(read_view_model(result.config_path));
  const RunPlayback playback(options.run_dir, scene, options.twin, options.leader);
  result.sources = playback.sources();
  const double start = std::clamp(options.start_s, 0.0, playback.duration_s());
  const double end =
      std::isnan(options.end_s) ? playback.duration_s() : std::clamp(options.end_s, start, playback.duration_s());
  const double step = options.speed / options.fps;
  const int frames = static_cast<int>(std::floor((end - start) / step + 1e-9)) + 1;
  result.output = options.output.empty() ? (fs::path(options.run_dir) / "run.mp4").string() : options.output;

  // a hidden window for its OpenGL context; the frames go to the offscreen buffer
  GlWindow window("teleop render", 64, 64, false);
  SceneRenderer renderer(scene, options.width, options.height, options.samples);
  renderer.use_offscreen(true);
  const mjrRect rect{0, 0, options.width, options.height};
  if (renderer.offscreen_rect().width < options.width || renderer.offscreen_rect().height < options.height) {
    throw std::runtime_error(
        fmt::format("the offscreen buffer is {}x{}, smaller than the {}x{} asked for (the OpenGL's limit)",
                    renderer.offscreen_rect().width, renderer.offscreen_rect().height, options.width, options.height));
  }
  RenderSettings& settings = renderer.settings();
  // the traces carry positions only: contact points are right, MuJoCo's contact forces would not
  // be (they need the torques); the measured external force is drawn as an arrow instead
  settings.contacts = options.contacts;
  settings.shadows = options.shadows;
  settings.layers = {true, options.twin, options.leader};
  renderer.start_camera(options.camera, options.azimuth_deg, options.elevation_deg, options.distance_m);

  const std::string label = run_label(options.run_dir);
  std::string legend = "follower\tsolid";
  if (result.sources.find("twin.csv") != std::string::npos) legend += "\ntwin\tghost (blue)";
  if (result.sources.find("leader.csv") != std::string::npos) legend += "\nleader\tghost (orange)";
  if (options.contacts) legend += "\nexternal force\tarrow";
  auto draw = [&](double t) {
    playback.pose(scene, t);
    scene.update();
    renderer.set_arrows(options.contacts ? playback.forces(t) : std::vector<ForceArrow>{}, 0.01);
    renderer.render(rect, options.overlay ? fmt::format("{}\nt = {:.2f} s", label, t) : "",
                    options.overlay ? legend : "");
    return renderer.read(rect);
  };

  std::fprintf(log, "teleop render: %s (%s) in %s, %d frames of %.2f s to %.2f s at %g fps, %gx\n",
               options.run_dir.c_str(), result.sources.c_str(), fs::path(scene.spec().model_path).filename().c_str(),
               frames, start, end, options.fps, options.speed);
  std::fflush(log);
  std::unique_ptr<VideoWriter> video;
  if (is_video(result.output)) {
    video = std::make_unique<VideoWriter>(result.output, options.width, options.height, options.fps);
  } else {
    fs::create_directories(result.output);
  }
  for (int k = 0; k < frames && !runtime::shutdown_requested(); ++k) {
    const Image frame = draw(start + k * step);
    if (video) {
      video->write(frame);
    } else {
      write_png(frame, (fs::path(result.output) / fmt::format("frame_{:05d}.png", k)).string());
    }
    ++result.frames;
  }
  if (video) video->finish();
  if (!options.still.empty()) {
    const double at = std::isnan(options.still_at_s) ? 0.5 * (start + end)
                                                     : std::clamp(options.still_at_s, 0.0, playback.duration_s());
    write_png(draw(at), options.still);
    result.still = options.still;
  }
  result.run_s = end - start;
  result.render_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return result;
}

}  // namespace teleop::view
