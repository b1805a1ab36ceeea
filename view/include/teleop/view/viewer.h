#pragma once
// `teleop view`: a window showing the scene of a node's config posed live from the bus (the
// follower solid, the twin and the leader's command as ghosts), until it is closed. docs/view.md.

#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include "teleop/view/bus_layers.h"

namespace teleop::view {

struct ViewOptions {
  /// The follower or twin config whose scene is shown and whose transport section is used
  /// (domain, discovery, security), as the bus tools take it.
  std::string config_path;
  std::optional<int> domain_id;
  LayerChoice layers;
  bool contacts = true;
  bool stereo = false;
  bool shadows = true;
  /// The text over the picture: the topics' state, the frame rate, the keys.
  bool overlay = true;
  /// A camera of the model by name; empty: the free camera around the model.
  std::string camera;
  /// The free camera's start (NaN: the model's own).
  double azimuth_deg = std::numeric_limits<double>::quiet_NaN();
  double elevation_deg = std::numeric_limits<double>::quiet_NaN();
  double distance_m = 0;
  int width = 1280;
  int height = 800;
  /// Stop after this many frames (0: when the window is closed); with `screenshot`, the last one
  /// is written there as PNG.
  int frames = 0;
  std::string screenshot;
  /// With `frames`: wait up to this long [s] for every shown layer's first samples before
  /// counting frames; none by then is an error.
  double wait_s = 0;
  double max_fps = 60;
};

/// Runs the view; returns the exit code (0: closed, or the frames drawn; 1: no samples within
/// wait_s). Throws ConfigError for a bad config, DisplayError without a display, ImageError when
/// the screenshot cannot be written, std::runtime_error for a model or camera that does not load.
int run_view(const ViewOptions& options, FILE* out);

}  // namespace teleop::view
