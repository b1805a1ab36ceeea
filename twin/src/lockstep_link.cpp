#include "lockstep_link.h"

#include <algorithm>

#include "teleop/common/clock.h"
#include "teleop/transport/joint_fields.h"

namespace teleop::twin {

LockstepLink::LockstepLink(transport::Participant& participant, const std::string& node_name, size_t joints,
                           double timeout_s, double max_wait_s)
    : state_(participant, transport::topics::kLockstepState, node_name),
      command_(participant, transport::topics::kLockstepCommand),
      timeout_ns_(static_cast<int64_t>(timeout_s * 1e9)),
      max_wait_ns_(static_cast<int64_t>(max_wait_s * 1e9)) {
  state_.sample().robot("twin");
  state_.sample().arm("lockstep");
  transport::presize_joint_state(state_.sample(), joints);
}

bool LockstepLink::connected() const { return state_.matched() > 0 && command_.reader().matched() > 0; }

bool LockstepLink::answered(uint64_t step) const {
  return command_.has_sample() && command_.latest().header().seq() >= step;
}

LockstepLink::Result LockstepLink::exchange() {
  const uint64_t step = answered_ + 1;
  if (!awaiting_) {
    // the header's sequence number is the step: the controller answers with its own n-th sample
    state_.publish();
    sent_ns_ = monotonic_now_ns();
    resent_ns_ = sent_ns_;
    awaiting_ = true;
  } else if (step == 1 && monotonic_now_ns() - resent_ns_ > static_cast<int64_t>(kFirstStepResendS * 1e9)) {
    state_.resend();
    resent_ns_ = monotonic_now_ns();
    ++resends_;
  }
  command_.poll();
  if (!answered(step) && command_.wait_for_data(max_wait_ns_)) command_.poll();
  if (!answered(step)) {
    const int64_t timeout_ns =
        step == 1 ? std::max(timeout_ns_, static_cast<int64_t>(kFirstStepTimeoutS * 1e9)) : timeout_ns_;
    return monotonic_now_ns() - sent_ns_ > timeout_ns ? Result::kStalled : Result::kPending;
  }
  awaiting_ = false;
  answered_ = step;
  return Result::kCommand;
}

}  // namespace teleop::twin
