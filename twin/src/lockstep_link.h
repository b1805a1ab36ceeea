#pragma once
// The twin's side of a lock-step exchange with an external controller process (thesis §3.4):
// the state of step n goes out, the command of step n (the controller's n-th sample) comes back,
// over reliable topics, so the sequence of states and commands does not depend on scheduling.
// The wait is bounded: a controller that stops answering is a stall, reported, never a hang.

#include <teleop/msg/arm.h>

#include "teleop/transport/publication.h"
#include "teleop/transport/subscription.h"

namespace teleop::twin {

class LockstepLink {
 public:
  /// Setup time: creates the reliable writer and reader.
  /// `max_wait_s`: the longest one exchange() blocks (a loop period, so the node's status keeps
  /// flowing while it waits).
  LockstepLink(transport::Participant& participant, const std::string& node_name, size_t joints, double timeout_s,
               double max_wait_s);

  /// Both directions matched with a controller.
  bool connected() const;
  /// The state to fill before exchange().
  msg::JointState& state() { return state_.sample(); }

  enum class Result {
    kCommand,  ///< the command of the current step is there: step now
    kPending,  ///< not yet, within the timeout: call again next cycle
    kStalled,  ///< not within the timeout since the state went out (the first step: kFirstStepTimeoutS)
  };
  /// The first step's answer may wait on discovery, which a loaded host can draw out beyond a
  /// running controller's timeout (both ends see each other, the controller's reply does not get
  /// through yet): the stall timeout of the first step is at least this.
  static constexpr double kFirstStepTimeoutS = 5.0;
  /// The twin counts as connected once *a* reader of its state is matched, which may be an
  /// observer's before the controller's: the first state can then miss the controller for good
  /// (volatile durability). Until the first answer, the state of step 1 goes out again this often;
  /// the controller answers a step once, so a repeat it already has is ignored.
  static constexpr double kFirstStepResendS = 0.1;
  /// Sends the state of the next step (unless it already went out and is still unanswered) and
  /// waits up to `max_wait_s` for the command of that step.
  [[nodiscard]] Result exchange();
  /// The command of the current step (valid after kCommand).
  const msg::JointCommand& command() const { return command_.latest(); }
  /// Steps whose command arrived.
  uint64_t steps() const { return answered_; }
  /// Repeats of the first step's state (kFirstStepResendS).
  uint64_t first_step_resends() const { return resends_; }

  const transport::Publication<msg::JointState>& state_publication() const { return state_; }
  const transport::Subscription<msg::JointCommand>& command_subscription() const { return command_; }

 private:
  bool answered(uint64_t step) const;

  transport::Publication<msg::JointState> state_;
  transport::Subscription<msg::JointCommand> command_;
  int64_t timeout_ns_;
  int64_t max_wait_ns_;
  int64_t sent_ns_ = 0;
  int64_t resent_ns_ = 0;
  uint64_t resends_ = 0;
  uint64_t answered_ = 0;
  bool awaiting_ = false;
};

}  // namespace teleop::twin
