#pragma once
// The model of a view with one simulation state per layer: the follower's measured state (drawn
// solid, with its contacts), the twin's state and the leader's command (drawn as ghosts). Each
// layer is posed from samples (joint positions of each arm, poses of free objects) and shown only
// once it has been posed: a viewer never draws a pose nobody measured. Not thread-safe: one
// thread poses and draws.

#include <mujoco/mujoco.h>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "teleop/sim/actuated_joints.h"
#include "teleop/sim/mujoco_model.h"
#include "teleop/view/view_model.h"

namespace teleop::view {

enum class Layer { kFollower = 0, kTwin = 1, kLeader = 2 };
inline constexpr size_t kLayerCount = 3;
const char* layer_name(Layer layer);

/// A body with a free joint (an object on the table): posed by its tracked pose, if any.
struct FreeBody {
  std::string name;
  int body = -1;
  int qpos = -1;  ///< address of its 7 coordinates (position, quaternion w x y z)
  int dof = -1;
};

class PosedScene {
 public:
  /// Loads the model, finds each arm's joints, starts every layer in the keyframe. Throws
  /// std::runtime_error naming the model on a model that does not load, a keyframe or arm it lacks.
  explicit PosedScene(const ViewModelSpec& spec);
  PosedScene(const PosedScene&) = delete;
  PosedScene& operator=(const PosedScene&) = delete;
  ~PosedScene();

  const mjModel* model() const { return sim_.model(); }
  /// For the renderer's context (its offscreen buffer size is a model setting).
  mjModel* model() { return sim_.model(); }
  mjData* data(Layer layer) { return data_[index(layer)]; }
  const ViewModelSpec& spec() const { return spec_; }

  size_t arm_count() const { return spec_.arms.size(); }
  const ViewArm& arm(size_t i) const { return spec_.arms[i]; }
  size_t joint_count(size_t arm) const { return joints_[arm].count; }
  /// The arm's flange site (-1: the model has none of its name).
  int ee_site(size_t arm) const { return ee_sites_[arm]; }
  const std::vector<FreeBody>& free_bodies() const { return free_bodies_; }

  /// Poses `arm`'s joints in `layer` from `n` positions, and optionally velocities and the joint
  /// torques acting (the follower's measured torques: with them its contact forces are the ones
  /// the follower's own simulation computes at that state). False, changing nothing, when `n` is
  /// not the arm's joint count.
  bool set_joints(Layer layer, size_t arm, const double* q, size_t n, const double* dq = nullptr,
                  const double* tau = nullptr);
  /// Poses a free body (its index in free_bodies()) in `layer`: position [m] and quaternion
  /// (w, x, y, z), world frame.
  void set_body_pose(Layer layer, size_t free_body, const double* position, const double* quaternion);

  /// True once any arm of `layer` was posed.
  bool posed(Layer layer) const { return posed_[index(layer)]; }
  /// Forgets the layer's poses: back to the keyframe, not shown.
  void clear(Layer layer);

  /// Recomputes what the renderer reads: the follower's forward dynamics (contacts and their
  /// forces), the ghosts' positions only.
  void update();

  /// Whether `body` is moved by an arm's joints (what a ghost layer draws).
  bool moved_by_arms(int body) const { return moved_by_arms_[static_cast<size_t>(body)]; }

 private:
  static size_t index(Layer layer) { return static_cast<size_t>(layer); }
  void reset_layer(size_t layer);

  ViewModelSpec spec_;
  sim::MujocoModel sim_;
  int keyframe_ = -1;
  std::vector<sim::ActuatedJoints> joints_;
  std::vector<int> ee_sites_;
  std::vector<FreeBody> free_bodies_;
  std::vector<bool> moved_by_arms_;
  std::array<mjData*, kLayerCount> data_{};
  std::array<bool, kLayerCount> posed_{};
};

}  // namespace teleop::view
