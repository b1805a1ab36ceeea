#include "lockstep_controller.h"

#include <chrono>
#include <cmath>
#include <thread>

#include "teleop/common/clock.h"
#include "teleop/runtime/shutdown_signal.h"
#include "teleop/transport/publication.h"
#include "teleop/transport/subscription.h"

namespace teleop::twin {

LockstepController::LockstepController(transport::Participant& participant, const LockstepControllerConfig& config)
    : participant_(participant), config_(config) {}

void LockstepController::compute(const msg::JointState& state, uint64_t step, msg::JointCommand& command) {
  const size_t n = state.q_rad().size();
  if (!have_origin_) {
    origin_rad_ = state.q_rad();
    have_origin_ = true;
  }
  const double t = static_cast<double>(step - 1) * config_.period_s;
  const double w = 2.0 * M_PI * config_.frequency_hz;
  command.q_des_rad().resize(n);
  command.dq_des_radps().resize(n);
  command.tau_ff_nm().assign(n, 0.0);
  command.stiffness_nm_per_rad().assign(n, config_.stiffness_nm_per_rad);
  command.damping_nms_per_rad().assign(n, config_.damping_nms_per_rad);
  command.mode().assign(n, msg::CONTROL_JOINT_IMPEDANCE);
  for (size_t i = 0; i < n; ++i) {
    // alternate joints swing in opposite directions
    const double a = (i % 2 == 0 ? 1.0 : -0.5) * config_.amplitude_rad;
    command.q_des_rad()[i] = origin_rad_[i] + a * std::sin(w * t);
    command.dq_des_radps()[i] = a * w * std::cos(w * t);
  }
}

uint64_t LockstepController::run() {
  transport::Subscription<msg::JointState> states(participant_, transport::topics::kLockstepState);
  transport::Publication<msg::JointCommand> commands(participant_, transport::topics::kLockstepCommand, "controller");
  uint64_t sent = 0;
  int64_t last_state_ns = monotonic_now_ns();
  const auto idle_ns = static_cast<int64_t>(config_.idle_timeout_s * 1e9);
  while (!runtime::shutdown_requested()) {
    if (config_.stall_after > 0 && sent >= config_.stall_after) {
      // a stalled controller: alive, but silent
      states.wait_for_data(100'000'000);
      continue;
    }
    if (!states.wait_for_data(100'000'000)) {
      if (monotonic_now_ns() - last_state_ns > idle_ns) break;
      continue;
    }
    last_state_ns = monotonic_now_ns();
    // the twin sends state n+1 only after command n arrived: at most one state is new
    if (states.poll() == 0 || states.latest().header().seq() <= sent) continue;
    // the reply must reach the twin: wait until our writer knows its reader
    while (commands.matched() == 0 && !runtime::shutdown_requested()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    compute(states.latest(), states.latest().header().seq(), commands.sample());
    commands.publish();
    ++sent;
  }
  return sent;
}

}  // namespace teleop::twin
