#pragma once
// The controller the twin runs in hardware-in-the-loop mode (PARTI §2.2): from the measured state
// of the real robot it commands a smooth joint trajectory to a goal, as joint impedance commands
// the robot executes. Real-time safe after construction.

#include <teleop/msg/arm.h>

#include "twin_config.h"

namespace teleop::twin {

class HilController {
 public:
  HilController(const HilConfig& config, size_t joints);

  /// Sizes the command's sequences (setup time).
  void presize(msg::JointCommand& cmd) const;
  /// Fills `cmd` for the measured `q_rad` at `t_s` since the first call (whose state is the start).
  void compute(const JointVector& q_rad, double t_s, msg::JointCommand& cmd);
  /// Largest |goal - q| over the joints [rad].
  double goal_error_rad(const JointVector& q_rad) const;

 private:
  HilConfig config_;
  size_t joints_;
  bool started_ = false;
  JointVector start_rad_{};
};

}  // namespace teleop::twin
