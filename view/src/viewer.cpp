#include "teleop/view/viewer.h"

#include <spdlog/fmt/fmt.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <thread>

#include "teleop/common/clock.h"
#include "teleop/runtime/shutdown_signal.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/participant_config.h"
#include "teleop/view/gl_window.h"
#include "teleop/view/posed_scene.h"
#include "teleop/view/scene_renderer.h"
#include "teleop/view/view_input.h"
#include "teleop/view/view_model.h"

namespace teleop::view {
namespace {

const std::array<Layer, 3> kLayers{Layer::kFollower, Layer::kTwin, Layer::kLeader};
// the external force's arrow: 1 cm per N (as teleop render's)
constexpr double kMetresPerNewton = 0.01;

bool layer_read(Layer layer, const LayerChoice& choice) {
  return layer == Layer::kFollower || (layer == Layer::kTwin && choice.twin) ||
         (layer == Layer::kLeader && choice.leader);
}


}  // namespace

int run_view(const ViewOptions& options, FILE* out) {
  PosedScene scene(read_view_model(options.config_path));
  const LayerChoice layers = shown_layers(scene, options.layers);
  const transport::ParticipantConfig bus_config =
      transport::tool_participant_config(options.config_path, options.domain_id, "view");
  // the window before the bus: without a display nothing joins the domain
  const std::string model_name = std::filesystem::path(scene.spec().model_path).filename().string();
  GlWindow window(fmt::format("teleop view: {} (domain {})", model_name, bus_config.domain_id), options.width,
                  options.height, true);
  SceneRenderer renderer(scene);
  RenderSettings& settings = renderer.settings();
  settings.contacts = options.contacts;
  settings.stereo = options.stereo;
  settings.shadows = options.shadows;
  settings.layers = {true, layers.twin, layers.leader};
  renderer.start_camera(options.camera, options.azimuth_deg, options.elevation_deg, options.distance_m);
  ViewInput input(window, renderer, scene.model());

  transport::Participant participant(bus_config);
  BusLayers bus(participant, scene, layers);
  std::string topics;
  for (Layer l : kLayers) {
    if (layer_read(l, layers))
      topics += fmt::format("{}{} ({})", topics.empty() ? "" : ", ", layer_name(l),
                            l == Layer::kFollower ? "solid" : "ghost");
  }
  std::fprintf(out, "teleop view: %s from %s in domain %d: %s; F1 in the window lists the keys\n", model_name.c_str(),
               scene.spec().source.c_str(), bus_config.domain_id, topics.c_str());
  std::fflush(out);

  const int64_t start_ns = monotonic_now_ns();
  const int64_t period_ns = options.max_fps > 0 ? static_cast<int64_t>(1e9 / options.max_fps) : 0;
  int64_t next_ns = start_ns;
  int counted = 0;
  int drawn = 0;
  double fps = 0;
  int64_t fps_since_ns = start_ns;
  int fps_frames = 0;
  while (!window.close_requested() && !runtime::shutdown_requested()) {
    window.poll_events();
    if (!input.frozen() || input.take_step()) {
      bus.update(scene);
      scene.update();
      renderer.set_arrows(bus.forces(scene), kMetresPerNewton);
    }
    const int64_t now_ns = monotonic_now_ns();
    bool ready = true;
    for (Layer l : kLayers) ready = ready && (!layer_read(l, layers) || bus.complete(l));
    if (options.frames > 0 && !ready && options.wait_s > 0 &&
        now_ns - start_ns > static_cast<int64_t>(options.wait_s * 1e9)) {
      std::string missing;
      for (Layer l : kLayers) {
        if (!layer_read(l, layers)) continue;
        const std::string m = bus.missing(l);
        if (!m.empty()) missing += (missing.empty() ? "" : ", ") + m;
      }
      std::fprintf(stderr, "teleop view: no samples on %s in domain %d within %g s (is the node running there?)\n",
                   missing.empty() ? "some topic (the wrong joint count)" : missing.c_str(), bus_config.domain_id,
                   options.wait_s);
      return 1;
    }
    std::string top;
    std::string bottom;
    if (options.overlay) {
      top = bus.status(system_now_ns());
      if (input.frozen()) top += "\nFROZEN\tSpace: go on, Right: one step";
      bottom = input.help_shown() ? std::string(kKeyHelp) : fmt::format("{:.0f} fps\tF1: keys", fps);
    }
    const mjrRect viewport = window.framebuffer();
    renderer.render(viewport, top, bottom);
    ++drawn;
    ++fps_frames;
    if (now_ns - fps_since_ns > 500'000'000) {
      fps = fps_frames * 1e9 / static_cast<double>(now_ns - fps_since_ns);
      fps_since_ns = now_ns;
      fps_frames = 0;
    }
    const bool counting = options.frames > 0 && (ready || options.wait_s <= 0);
    if (counting && ++counted >= options.frames) {
      if (!options.screenshot.empty()) write_png(renderer.read(viewport), options.screenshot);
      window.swap_buffers();
      break;
    }
    window.swap_buffers();
    next_ns += period_ns;
    const int64_t slack_ns = next_ns - monotonic_now_ns();
    if (slack_ns > 0) {
      std::this_thread::sleep_for(std::chrono::nanoseconds(slack_ns));
    } else {
      next_ns = monotonic_now_ns();
    }
  }
  const double seconds = static_cast<double>(monotonic_now_ns() - start_ns) * 1e-9;
  std::fprintf(
      out, "teleop view: %d frames in %.1f s (%.1f fps)%s\n", drawn, seconds, seconds > 0 ? drawn / seconds : 0.0,
      options.screenshot.empty() || counted < options.frames ? "" : (", screenshot " + options.screenshot).c_str());
  return 0;
}

}  // namespace teleop::view
