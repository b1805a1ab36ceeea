#pragma once
// The twin's side of MMT's model update: subscribes to the follower's joint state and estimated
// wrench, turns each new pair of samples into a SurfaceMeasurement on the twin's own copy of the
// arm (RemoteContactProbe), feeds the EnvironmentCorrection and moves the twin's environment geom
// to its applied offset. Setup allocates and throws; cycle() is real-time safe.

#include <teleop/msg/arm.h>

#include <array>
#include <string>
#include <vector>

#include "teleop/runtime/node_report.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/subscription.h"
#include "environment_correction.h"
#include "remote_contact_probe.h"
#include "teleop/twin/twin_simulation.h"

namespace teleop::twin {

class ModelCorrection {
 public:
  ModelCorrection(const CorrectionConfig& config, const TwinSimulation& sim, transport::Participant& participant);

  /// Takes what the follower sent since the last cycle, updates the estimate and moves the
  /// geom by at most the rate limit over `dt_s`. Call between steps.
  void cycle(TwinSimulation& sim, double dt_s);

  const EnvironmentCorrection& correction() const { return correction_; }

  void fill_report(runtime::NodeReport& report) const;
  void trace_columns(std::vector<std::string>& columns) const;
  /// Writes the trace_columns() values; returns the position after them.
  double* trace_row(double* row) const;

 private:
  void measure(const TwinSimulation& sim);

  CorrectionConfig config_;
  RemoteContactProbe probe_;
  EnvironmentCorrection correction_;
  std::array<double, 3> base_pos_m_{};
  transport::Subscription<msg::JointState> state_;
  transport::Subscription<msg::WrenchStamped> wrench_;
  JointVector q_{};
  double last_gap_m_ = 0.0;
  double last_force_n_ = 0.0;
  uint64_t unpaired_ = 0;
  uint64_t malformed_ = 0;
};

}  // namespace teleop::twin
