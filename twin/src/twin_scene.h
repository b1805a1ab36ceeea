#pragma once
// The world of a multi-arm twin (twin.arms): ONE simulation of the whole scene, every arm's
// joints driven by the coupling of PARTI eq. 2 towards its own target, the objects between the
// arms (the box task's box) shared, as the follower's MujocoScene shares them. The arms
// (TwinArm) write their targets in their cycles; the scene then steps once for all of them. It
// is the unnamed member of the twin's ArmGroup: its report keeps the one-arm twin's names
// (sim_time_s, rt_factor, mujoco_warnings, ...). Setup allocates and throws; the rest does not.

#include <memory>
#include <optional>

#include "teleop/runtime/node_runner.h"
#include "object_tracking.h"
#include "teleop/twin/twin_model_config.h"
#include "twin_observations.h"
#include "teleop/twin/twin_simulation.h"

namespace teleop::twin {

class TwinScene final : public runtime::NodeLogic {
 public:
  /// Loads `model` (throws std::runtime_error naming the file) at the loop's period; with
  /// `objects`, the remote site's measurements of those bodies pull the twin's (ObjectTracking).
  TwinScene(const TwinModelConfig& model, const std::optional<ObjectCorrectionConfig>& objects,
            runtime::NodeContext& context);

  /// The coupling targets of every driven joint, each arm's at its own offset. Between steps.
  JointVector& targets() { return targets_; }
  /// One control period coupled to the targets, then the scene's observations. Real-time safe.
  void step();

  const TwinSimulation& simulation() const { return sim_; }

  /// Notes the cycle's time; the stepping waits for the arms (step()).
  void cycle(const CycleTick& tick) override { observations_.mark_cycle(tick.now_ns); }
  /// The arms report their own states; the scene itself is always running.
  msg::NodeState state() const override { return msg::STATE_RUNNING; }
  void active_faults(std::vector<uint32_t>&) const override {}
  void fill_report(runtime::NodeReport& report) const override;
  /// The contact forces and distances of the configured pairs (model.contact_pairs,
  /// distance_pairs), then each corrected object's error and pull.
  void trace_columns(std::vector<std::string>& columns) const override;
  void trace_row(double* row) const override;

 private:
  TwinSimulation sim_;
  TwinObservations observations_;
  JointVector targets_;
  std::unique_ptr<ObjectTracking> objects_;
};

}  // namespace teleop::twin
