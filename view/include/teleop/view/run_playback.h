#pragma once
// A recorded run posing a view: the traces a run left in its folder (`teleop launch --trace-dir`,
// an experiment's <report dir>/<run>/<profile>/) read back and interpolated in time. The
// follower's trace (follower.csv: q_<i>, or <arm>_q_<i> per arm) poses the follower's layer,
// the twin's (twin.csv) the twin's ghost; a free body's position comes from <body>_x/_y/_z
// columns when the follower's trace has them (the box task's), its orientation stays the
// keyframe's; the external force at each flange (f_ext_*, at x_*) becomes an arrow.

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "teleop/experiment/trace.h"
#include "teleop/view/posed_scene.h"
#include "teleop/view/scene_renderer.h"

namespace teleop::view {

class RunPlayback {
 public:
  /// Reads `run_dir`/follower.csv (required) and twin.csv (when `twin` and it exists; as leader.csv
  /// for `leader`). Throws experiment::TraceError naming the file when a trace is unreadable or
  /// has no joint columns of an arm of `scene`.
  RunPlayback(const std::string& run_dir, const PosedScene& scene, bool twin, bool leader);

  /// Seconds from the follower's first row to its last.
  double duration_s() const;
  /// Poses `scene` at `t_s` after the follower's first row (clamped to the run).
  void pose(PosedScene& scene, double t_s) const;
  /// The external forces at the flanges at `t_s` (none when the trace has no f_ext columns).
  std::vector<ForceArrow> forces(double t_s) const;
  /// The traces used, for messages ("follower.csv, twin.csv").
  std::string sources() const;

 private:
  struct Series {
    Layer layer;
    std::string file;
    std::vector<double> time_s;                                                        // since the follower's first row
    std::vector<std::vector<const std::vector<double>*>> arm_q;                        // per arm: its joint columns
    std::vector<std::pair<size_t, std::array<const std::vector<double>*, 3>>> bodies;  // free body, x y z
    std::vector<std::pair<std::array<const std::vector<double>*, 3>, std::array<const std::vector<double>*, 3>>> forces;
    experiment::Trace trace;
  };
  Series read_series(const std::string& path, Layer layer, const PosedScene& scene, bool required) const;
  // the rows around `t_s` and the weight of the later one
  static void bracket(const Series& s, double t_s, size_t& i0, size_t& i1, double& w);

  std::vector<Series> series_;
  double origin_ = 0;  // the follower's first time stamp on the traces' common clock
};

}  // namespace teleop::view
