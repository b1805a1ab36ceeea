#pragma once
// An external controller process for the twin's lock-step mode (thesis §3.4): for every state
// sample n it receives it answers with exactly one command (its n-th sample), a joint impedance
// law that moves the arm along a sine about the first state it saw. Deterministic: the command
// depends only on the state and the step number. `stall_after` makes it stop answering after that
// many steps (to test the twin's stall detection).

#include <cstdint>
#include <vector>

#include <teleop/msg/arm.h>

#include "teleop/transport/participant.h"

namespace teleop::twin {

struct LockstepControllerConfig {
  double period_s = 0.001;
  double amplitude_rad = 0.3;
  double frequency_hz = 1.0;
  double stiffness_nm_per_rad = 200.0;
  double damping_nms_per_rad = 15.0;
  /// Stop answering after this many steps (0: never).
  uint64_t stall_after = 0;
  /// Give up when no state came for this long.
  double idle_timeout_s = 5.0;
};

class LockstepController {
 public:
  LockstepController(transport::Participant& participant, const LockstepControllerConfig& config);
  /// Answers states until a shutdown signal, `stall_after` steps, or the idle timeout. Returns the
  /// number of commands sent.
  uint64_t run();

  /// The command for state `state` at step `step` (1-based): a function of the two and of the first
  /// state seen. Sizes the command's sequences (allocates on the first call; not a 1 kHz loop).
  void compute(const msg::JointState& state, uint64_t step, msg::JointCommand& command);

 private:
  transport::Participant& participant_;
  LockstepControllerConfig config_;
  bool have_origin_ = false;
  std::vector<double> origin_rad_;
};

}  // namespace teleop::twin
