#pragma once
// Metrics of the two-arm box task (PARTI §3.3, docs/box_task.md): success, task time, squeeze-force
// variation and box slip, as pure functions of a sampled trace. The trace's columns (a node's
// trace CSV may carry them under these names) are kBoxTaskColumns, all in the robot base frame.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <vector>

namespace teleop::box_task {

/// Column names of a box task trace, in the order of BoxTaskSample's fields.
inline constexpr std::array<const char*, 14> kBoxTaskColumns = {
    "t_s",    "box_x",  "box_y",  "box_z",          "left_x",          "left_y",    "left_z",
    "right_x", "right_y", "right_z", "left_squeeze_n", "right_squeeze_n", "support_n", "arm_collision_n"};

/// One sample of the task (what BoxTaskProbe reads from a simulation).
struct BoxTaskSample {
  double t_s = 0;
  Eigen::Vector3d box_m = Eigen::Vector3d::Zero();    ///< box centre
  Eigen::Vector3d left_m = Eigen::Vector3d::Zero();   ///< left flange (ee site)
  Eigen::Vector3d right_m = Eigen::Vector3d::Zero();  ///< right flange
  double left_squeeze_n = 0;   ///< normal contact force between the left arm and the box
  double right_squeeze_n = 0;  ///< the same for the right arm
  double support_n = 0;        ///< normal contact force between the box and the environment
  double arm_collision_n = 0;  ///< normal contact force between an arm and anything but the box
};

/// The trace: samples with ascending times.
struct BoxTaskSeries {
  std::vector<BoxTaskSample> samples;
  void append(const BoxTaskSample& sample) { samples.push_back(sample); }
};

/// Axis-aligned region the box centre must lie in to be inside the shelf compartment.
struct BoxRegion {
  Eigen::Vector3d min_m;
  Eigen::Vector3d max_m;
  bool contains(const Eigen::Vector3d& p) const {
    return (p.array() >= min_m.array()).all() && (p.array() <= max_m.array()).all();
  }
};

struct BoxTaskThresholds {
  double contact_n = 0.5;        ///< a contact force at least this large counts as touching
  double debounce_s = 0.02;      ///< contact changes shorter than this are ignored (a flicker)
  double rest_window_s = 0.5;    ///< the box rests when it moved less than rest_motion_m in this window
  double rest_motion_m = 0.002;  ///< at the end of the trace
};

struct BoxTaskMetrics {
  bool success = false;    ///< in the shelf and resting there at the end, never dropped
  bool in_shelf = false;   ///< box centre inside the compartment region at the end
  bool resting = false;    ///< box still over the last rest_window_s, on a support
  double task_time_s = 0;  ///< start to placed (placed_time_s); NaN when never placed
  double carry_time_s = 0;  ///< time the box was held by both hands off its supports
  std::array<double, 2> squeeze_variation_n{};  ///< per hand (left, right): max - min over the carry
  std::array<double, 2> squeeze_min_n{};        ///< per hand: smallest squeeze over the carry
  double slip_mm = 0;       ///< largest box displacement in the hands' midpoint frame, carry
  bool dropped = false;     ///< off its supports without both hands on it for longer than debounce_s
  double max_arm_collision_n = 0;  ///< largest arm_collision_n: arms hitting furniture, body or each other
};

/// `mask` with every run of true samples that lasts less than `min_s` (first to last sample
/// time) turned false.
std::vector<bool> without_short_runs(const BoxTaskSeries& series, std::vector<bool> mask, double min_s);

/// Per sample: nothing supports the box (support_n < contact_n) for at least debounce_s.
std::vector<bool> unsupported_mask(const BoxTaskSeries& series, const BoxTaskThresholds& thresholds);

/// Per sample: both hands touch the box (squeeze >= contact_n) and nothing else supports it
/// (support_n < contact_n), for at least debounce_s: the carry phase.
std::vector<bool> carry_mask(const BoxTaskSeries& series, const BoxTaskThresholds& thresholds);

/// Whether the box was ever off its supports without being held by both hands for longer than
/// debounce_s (a fall; a single sample, e.g. a box settling into its first contact, is not one).
bool dropped(const BoxTaskSeries& series, const BoxTaskThresholds& thresholds);

/// Largest minus smallest of `values` over the samples in `mask`; NaN when there are none.
double variation_over(const std::vector<double>& values, const std::vector<bool>& mask);

/// The box centre in the hands' midpoint frame: origin midway between the flanges, y axis from
/// the right flange to the left one, z axis world up made normal to it, x = y cross z.
Eigen::Vector3d box_in_hand_frame(const BoxTaskSample& sample);

/// Largest |p(t) - p(t0)| [mm] of box_in_hand_frame over the samples in `mask`, t0 the first of
/// them; NaN when there are none.
double slip_mm(const BoxTaskSeries& series, const std::vector<bool>& mask);

/// First time from which on, to the end, the box centre is in `shelf` and supported (support
/// losses shorter than debounce_s ignored); NaN when the trace does not end so.
double placed_time_s(const BoxTaskSeries& series, const BoxRegion& shelf, const BoxTaskThresholds& thresholds);

/// Whether the box moved less than rest_motion_m over the last rest_window_s and is supported.
bool resting_at_end(const BoxTaskSeries& series, const BoxTaskThresholds& thresholds);

/// All metrics of one trace. An empty trace has every metric NaN or false.
BoxTaskMetrics evaluate_box_task(const BoxTaskSeries& series, const BoxRegion& shelf,
                                 const BoxTaskThresholds& thresholds = {});

}  // namespace teleop::box_task
