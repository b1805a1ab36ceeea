#pragma once
// `teleop render RUN_DIR`: a video (MP4 through ffmpeg) or PNG frames of a recorded run, posed
// from its traces (run_playback.h), rendered offscreen in a hidden window (a display is needed:
// under Xvfb on a machine without one), with the run's time written over each frame. docs/view.md.

#include <cstdio>
#include <limits>
#include <string>

namespace teleop::view {

struct RenderOptions {
  std::string run_dir;
  /// The follower or twin config whose scene is drawn; empty: the shipped follower config, or the
  /// box task's for a two-arm trace (left_/right_ columns).
  std::string config_path;
  /// An .mp4 (.mkv, .mov, .webm) file, or a folder for PNG frames (frame_00000.png, ...);
  /// empty: RUN_DIR/run.mp4.
  std::string output;
  /// Also one frame as PNG, at `still_at_s` (NaN: the middle of what is rendered).
  std::string still;
  double still_at_s = std::numeric_limits<double>::quiet_NaN();
  std::string camera;
  double azimuth_deg = std::numeric_limits<double>::quiet_NaN();
  double elevation_deg = std::numeric_limits<double>::quiet_NaN();
  double distance_m = 0;
  int width = 1280;
  int height = 720;
  double fps = 30;
  /// Run seconds per video second.
  double speed = 1;
  double start_s = 0;
  /// NaN: to the end of the run.
  double end_s = std::numeric_limits<double>::quiet_NaN();
  bool twin = true;
  bool leader = false;
  bool contacts = true;
  bool overlay = true;
  bool shadows = true;
  /// Multisamples per pixel (anti-aliasing); software OpenGL pays for each: 0 draws 1.4-1.6x faster.
  int samples = 4;
};

struct RenderResult {
  std::string output;
  std::string still;
  std::string config_path;
  std::string sources;
  int frames = 0;
  double run_s = 0;     ///< run time covered
  double render_s = 0;  ///< wall time it took
};

/// The node config a run's scene is taken from when none is given (see RenderOptions).
std::string default_scene_config(const std::string& run_dir);

/// Renders the run. Throws experiment::TraceError for unreadable traces, DisplayError without a
/// display, VideoError or ImageError when the output cannot be written, ConfigError for a bad
/// config, std::runtime_error for a model or camera that does not load. Logs progress to `log`.
RenderResult render_run(const RenderOptions& options, FILE* log);

}  // namespace teleop::view
