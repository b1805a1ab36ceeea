#include "view_command.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "config_option.h"
#include "teleop/common/config.h"
#include "teleop/common/data_paths.h"
#include "teleop/experiment/trace.h"
#include "teleop/runtime/shutdown_signal.h"
#include "teleop/tools/bag_tools.h"
#include "teleop/tools/recording_traces.h"
#include "teleop/view/gl_window.h"
#include "teleop/view/image.h"
#include "teleop/view/video_writer.h"

namespace teleop::cli {

namespace fs = std::filesystem;

namespace {

// where `teleop view` and `teleop render` start their camera (SceneRenderer::start_camera)
template <typename Options>
void add_camera_options(CLI::App* command, Options& o, const std::string& camera_help) {
  command->add_option("--camera", o.camera, camera_help);
  command->add_option("--azimuth", o.azimuth_deg, "the free camera's azimuth [deg]");
  command->add_option("--elevation", o.elevation_deg, "the free camera's elevation [deg]");
  command->add_option("--distance", o.distance_m, "the free camera's distance [m]")->check(CLI::PositiveNumber);
}

// a recording's joint states as the traces of a run, in RECORDING_traces/ (render poses from
// those); a recording that cannot be read, or holds no joint state, is a TraceError like a bad trace
std::string traces_of_recording(const std::string& recording) {
  const std::string dir = tools::recording_stem(recording) + "_traces";
  try {
    for (const std::string& file : tools::write_recording_traces(recording, dir)) {
      std::printf("teleop render: %s from %s\n", file.c_str(), recording.c_str());
    }
  } catch (const std::runtime_error& e) {
    throw experiment::TraceError(e.what());
  }
  return dir;
}

}  // namespace

ViewCommands::ViewCommands(CLI::App& app) {
  add_view(app);
  add_render(app);
}

void ViewCommands::add_view(CLI::App& app) {
  view_ = app.add_subcommand(
      "view",
      "a window with the 3D scene of a node's config posed live from the bus: the follower solid, the twin "
      "(and the leader's command) as ghosts, contacts and their forces; or the hand (docs/view.md)");
  view::ViewOptions& o = view_options_;
  view_
      ->add_option("-c,--config", o.config_path,
                   "the follower, twin or hand config whose scene to show and whose bus to join (domain, "
                   "discovery, security); a file or a name in config/nodes (default: follower); a hand config "
                   "shows the emulator's MuJoCo hand posed by teleop/hand/joint_state")
      ->transform(named_config("nodes"))
      ->check(CLI::ExistingFile);
  view_->add_option("--domain", o.domain_id, "DDS domain id (overrides the config)")->check(CLI::Range(0, 232));
  view_->add_flag("--no-twin", no_twin_, "no ghost of the twin (teleop/twin/joint_state)");
  view_->add_flag("--leader", o.layers.leader,
                  "a ghost of the leader's command (teleop/leader/joint_command; under MMT its device state, "
                  "teleop/leader/joint_state)");
  view_->add_flag("--no-contacts", no_contacts_, "no contact points and forces");
  view_->add_flag("--no-shadows", no_shadows_, "no shadows (faster on software OpenGL)");
  view_->add_flag("--no-overlay", no_overlay_, "no text over the picture");
  view_->add_flag("--stereo", o.stereo, "side-by-side stereo: the left eye's picture left, the right eye's right");
  add_camera_options(view_, o, "start with this camera of the model (default: the free camera)");
  view_->add_option("--width", o.width, "window width in pixels (default 1280)")->check(CLI::Range(64, 8192));
  view_->add_option("--height", o.height, "window height in pixels (default 800)")->check(CLI::Range(64, 8192));
  view_->add_option("--max-fps", o.max_fps, "frames per second at most (default 60)")->check(CLI::Range(1.0, 1000.0));
  view_->add_option("--frames", o.frames, "stop after this many frames (default: when the window is closed)")
      ->check(CLI::PositiveNumber);
  view_->add_option("--screenshot", o.screenshot, "write the last frame as PNG (with --frames)")->needs("--frames");
  view_
      ->add_option("--wait", o.wait_s,
                   "with --frames: count frames only once every shown topic delivered, waiting at most this many "
                   "seconds (none by then: exit 1)")
      ->check(CLI::NonNegativeNumber)
      ->needs("--frames");
}

void ViewCommands::add_render(CLI::App& app) {
  render_ = app.add_subcommand(
      "render",
      "a video (MP4) or PNG frames of a recorded run from its traces, offscreen, with the run's time "
      "(docs/view.md)");
  view::RenderOptions& o = render_options_;
  render_
      ->add_option("run_dir", o.run_dir,
                   "the run's trace folder (teleop launch --trace-dir, or <report dir>/<run>/<profile> of an "
                   "experiment): follower.csv, and twin.csv when there is one; or a recording (an MCAP file, a "
                   "sqlite3 bag folder), whose joint states become such traces in RUN_DIR_traces/")
      ->required()
      ->check(CLI::ExistingPath);
  render_
      ->add_option("-c,--config", o.config_path,
                   "the follower or twin config whose scene to draw (default: follower, or follower_box_task for a "
                   "two-arm trace)")
      ->transform(named_config("nodes"))
      ->check(CLI::ExistingFile);
  render_->add_option("-o,--output", o.output, "an .mp4 file, or a folder for PNG frames (default: RUN_DIR/run.mp4)");
  render_->add_option("--still", o.still, "also write one frame as PNG");
  render_->add_option("--still-at", o.still_at_s, "the still's run time [s] (default: the middle)")
      ->check(CLI::NonNegativeNumber);
  add_camera_options(render_, o, "a camera of the model (default: the free camera)");
  render_->add_option("--width", o.width, "frame width in pixels, even (default 1280)")->check(CLI::Range(64, 4096));
  render_->add_option("--height", o.height, "frame height in pixels, even (default 720)")->check(CLI::Range(64, 4096));
  render_->add_option("--fps", o.fps, "frames per second of video (default 30)")->check(CLI::Range(1.0, 240.0));
  render_->add_option("--speed", o.speed, "run seconds per video second (default 1)")->check(CLI::Range(0.01, 100.0));
  render_->add_option("--from", o.start_s, "start at this run time [s]")->check(CLI::NonNegativeNumber);
  render_->add_option("--to", o.end_s, "end at this run time [s] (default: the end)")->check(CLI::NonNegativeNumber);
  render_->add_flag("--no-twin", no_twin_, "no ghost of the twin");
  render_->add_flag("--leader", o.leader,
                    "a ghost of the leader's positions (leader.csv, same joints as the follower)");
  render_->add_flag("--no-contacts", no_contacts_, "no contact points and no external-force arrows");
  render_->add_flag("--no-shadows", no_shadows_, "no shadows (faster)");
  render_->add_option("--samples", o.samples, "multisamples per pixel, anti-aliasing (default 4; 0 is faster)")
      ->check(CLI::Range(0, 16));
  render_->add_flag("--no-overlay", no_overlay_, "no run name and time over the frames");
}

void ViewCommands::add_experiment_option(CLI::App* experiment) {
  experiment->add_flag(
      "--render", experiment_render_,
      "also a video of each run (<run>/<profile>/run.mp4 and run.png, `teleop render`; needs a display "
      "or Xvfb)");
}

int ViewCommands::render_experiment(const std::string& report_dir) const {
  if (!experiment_render_) return 0;
  int failed = 0;
  std::vector<fs::path> runs;
  for (const auto& entry : fs::recursive_directory_iterator(report_dir)) {
    if (entry.is_regular_file() && entry.path().filename() == "follower.csv")
      runs.push_back(entry.path().parent_path());
  }
  std::sort(runs.begin(), runs.end());
  for (const fs::path& dir : runs) {
    view::RenderOptions o;
    o.run_dir = dir.string();
    o.still = (dir / "run.png").string();
    try {
      const view::RenderResult r = view::render_run(o, stdout);
      std::printf("video: %s (%d frames), still: %s\n", r.output.c_str(), r.frames, r.still.c_str());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "teleop experiment --render: %s: %s\n", dir.c_str(), e.what());
      ++failed;
    }
  }
  return failed;
}

std::optional<int> ViewCommands::run() {
  if (!view_->parsed() && !render_->parsed()) return std::nullopt;
  runtime::install_shutdown_handlers();
  try {
    if (view_->parsed()) {
      view::ViewOptions o = view_options_;
      if (o.config_path.empty()) o.config_path = view::shipped_node_config("follower");
      o.layers.twin = !no_twin_;
      o.contacts = !no_contacts_;
      o.shadows = !no_shadows_;
      o.overlay = !no_overlay_;
      return view::run_view(o, stdout);
    }
    view::RenderOptions o = render_options_;
    if (tools::is_recording(o.run_dir)) o.run_dir = traces_of_recording(o.run_dir);
    o.twin = !no_twin_;
    o.contacts = !no_contacts_;
    o.shadows = !no_shadows_;
    o.overlay = !no_overlay_;
    const view::RenderResult r = view::render_run(o, stdout);
    std::printf("teleop render: %d frames (%.2f s of the run) in %.1f s: %s%s\n", r.frames, r.run_s, r.render_s,
                r.output.c_str(), r.still.empty() ? "" : (", still " + r.still).c_str());
    return 0;
  } catch (const view::DisplayError& e) {
    std::fprintf(stderr, "teleop %s: %s\n", view_->parsed() ? "view" : "render", e.what());
    return 1;
  } catch (const experiment::TraceError& e) {
    std::fprintf(stderr, "teleop render: %s\n", e.what());
    return 1;
  }
}

}  // namespace teleop::cli
