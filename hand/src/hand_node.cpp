#include "teleop/hand/hand_node.h"

#include <time.h>

#include <algorithm>
#include <stdexcept>
#include <string>

#include <spdlog/spdlog.h>

#include "teleop/can/socketcan_bus.h"
#include "teleop/common/clock.h"
#include "teleop/runtime/shutdown_signal.h"
#include "teleop/transport/joint_fields.h"

namespace teleop::hand {

namespace {

// the adapter's fault bits are the IDL's, so HandState carries them unchanged
static_assert(hand_fault::kEmcy == msg::HAND_FAULT_EMCY);
static_assert(hand_fault::kHeartbeat == msg::HAND_FAULT_HEARTBEAT);
static_assert(hand_fault::kDrive == msg::HAND_FAULT_DRIVE);
static_assert(hand_fault::kLimit == msg::HAND_FAULT_LIMIT);
static_assert(hand_fault::kOverCurrent == msg::HAND_FAULT_OVERCURRENT);
static_assert(hand_fault::kBusOff == msg::HAND_FAULT_BUS_OFF);
static_assert(hand_fault::kStalePdo == msg::HAND_FAULT_STALE_PDO);
static_assert(hand_fault::kBusPassive == msg::HAND_FAULT_BUS_PASSIVE);
static_assert(hand_fault::kSdo == msg::HAND_FAULT_SDO);
static_assert(msg::HAND_MOTORS == kHandMotors);

std::unique_ptr<can::CanBus> open_socketcan(const HandNodeConfig& config) {
  can::SocketCanOptions options;
  options.filters = can::canopen_master_filters(config.adapter.node_ids);
  return std::make_unique<can::SocketCanBus>(config.interface, options);
}

HandAdapterConfig with_rate(HandAdapterConfig config, double rate_hz) {
  config.cycle_rate_hz = rate_hz;
  return config;
}

void sleep_until_ns(int64_t deadline_ns) {
  const timespec t{static_cast<time_t>(deadline_ns / 1'000'000'000), static_cast<long>(deadline_ns % 1'000'000'000)};
  ::clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &t, nullptr);
}

}  // namespace

HandNode::HandNode(const HandNodeConfig& config, runtime::NodeContext& context)
    : HandNode(config, context, open_socketcan(config)) {}

HandNode::HandNode(const HandNodeConfig& config, runtime::NodeContext& context, std::unique_ptr<can::CanBus> bus)
    : config_(config),
      bus_(std::move(bus)),
      adapter_(*bus_, with_rate(config.adapter, context.node.rate_hz)),
      command_(context.participant, transport::topics::kHandCommand),
      state_pub_(context.participant, transport::topics::kHandState, context.node.name),
      joints_pub_(context.participant, transport::topics::kHandJoints, context.node.name) {
  if (const auto warning = bus_load_warning(adapter_.config())) spdlog::warn("{}: {}", context.node.name, *warning);
  const HandBusBudget& budget = adapter_.bus_budget();
  spdlog::info("{}: {} at {:.0f} Hz, bus load {:.1f} % nominal / {:.1f} % worst case", context.node.name,
               config.interface, context.node.rate_hz, budget.load.load_nominal * 100,
               budget.load.load_worst_case * 100);
  auto& joints = joints_pub_.sample();
  joints.robot("svh_hand");
  joints.arm("hand");
  transport::presize_joint_state(joints, kHandJoints);
  start_up(context.node.period_ns());
  targets_.position_rad = adapter_.feedback().target_rad;
  targets_.enable = true;
  spdlog::info("{}: hand operational ({} SDO writes, {} cycles to start)", context.node.name,
               adapter_.stats().sdo_writes, adapter_.stats().cycles);
}

void HandNode::start_up(int64_t period_ns) {
  int64_t next = monotonic_now_ns();
  HandPhase reported = adapter_.phase();
  while (!adapter_.started()) {
    adapter_.cycle(next);
    if (adapter_.phase() != reported) {
      reported = adapter_.phase();
      spdlog::info("hand: {}", to_string(reported));
    }
    if (reported == HandPhase::kFailed || reported == HandPhase::kSafeHold) {
      throw std::runtime_error(std::string("start-up failed: ") + adapter_.message());
    }
    if (runtime::shutdown_requested()) throw std::runtime_error("start-up interrupted");
    next += period_ns;
    sleep_until_ns(next);
  }
}

void HandNode::take_command() {
  const msg::HandCommand& c = command_.latest();
  for (size_t m = 0; m < kHandMotors; ++m) {
    targets_.position_rad[m] = c.target_position_rad()[m];
    targets_.current_limit_a[m] = c.current_limit_a()[m];
  }
  targets_.enable = c.enable();
  targets_.fault_reset = c.fault_reset();
  if (!emergency_stopped_) adapter_.set_command(targets_);
}

void HandNode::emergency_stop(bool engaged) {
  emergency_stopped_ = engaged;
  // the newest command again at the enable; until then the hand's own quick stop and hold
  HandTargets targets = targets_;
  if (engaged) targets.enable = false;
  targets.fault_reset = false;
  adapter_.set_command(targets);
}

void HandNode::cycle(const CycleTick& tick) {
  if (command_.poll() > 0) take_command();
  // a silent commander: the hand keeps its last targets (the adapter holds them)
  command_stale_ = !command_.has_sample() ||
                   command_.age_ns(tick.now_ns) > static_cast<int64_t>(config_.command_timeout_s * 1e9);
  adapter_.cycle(tick.now_ns);
  publish();
}

void HandNode::publish() {
  const HandFeedback& fb = adapter_.feedback();
  msg::HandState& s = state_pub_.sample();
  s.position_rad() = fb.position_rad;
  s.velocity_radps() = fb.velocity_radps;
  s.current_a() = fb.current_a;
  s.statusword() = fb.statusword;
  s.error_code() = fb.error_code;
  s.faults() = fb.faults;
  state_pub_.publish();

  const HandJointVector q = adapter_.joint_positions();
  msg::JointState& j = joints_pub_.sample();
  std::copy(q.begin(), q.end(), j.q_rad().begin());
  const HandJointVector dq = adapter_.joint_velocities();
  std::copy(dq.begin(), dq.end(), j.dq_radps().begin());
  joints_pub_.publish();
}

msg::NodeState HandNode::state() const {
  switch (adapter_.phase()) {
    case HandPhase::kOperational:
      return msg::STATE_RUNNING;
    case HandPhase::kSafeHold:
      return msg::STATE_SAFE_HOLD;
    case HandPhase::kFailed:
      return msg::STATE_FAULT;
    default:
      return msg::STATE_STARTING;
  }
}

void HandNode::fill_status(msg::NodeStatus& status) const {
  status.can_bus_state(can::to_string(bus_->state()));
}

void HandNode::active_faults(std::vector<uint32_t>& faults) const {
  const auto& f = adapter_.feedback().faults;
  constexpr uint32_t kMomentary = hand_fault::kLimit | hand_fault::kOverCurrent;
  if (std::any_of(f.begin(), f.end(), [](uint32_t bits) { return (bits & ~kMomentary) != 0; })) {
    faults.push_back(msg::FAULT_HARDWARE);
  }
  if (command_stale_) faults.push_back(msg::FAULT_STALE_INPUT);
  const HandAdapterStats& s = adapter_.stats();
  if (s.clamped_commands + s.rejected_commands > 0) faults.push_back(msg::FAULT_COMMAND_REJECTED);
}

void HandNode::fill_report(runtime::NodeReport& report) const {
  report.add(command_);
  report.add(state_pub_);
  report.add(joints_pub_);
  const HandAdapterStats& s = adapter_.stats();
  const std::pair<const char*, uint64_t> counters[] = {
      {"hand_cycles", s.cycles},           {"hand_syncs_sent", s.syncs_sent},
      {"hand_tpdos_received", s.tpdos_received}, {"hand_send_failures", s.send_failures},
      {"hand_emcys", s.emcys},             {"hand_sdo_writes", s.sdo_writes},
      {"hand_sdo_aborts", s.sdo_aborts},   {"hand_unexpected_frames", s.unexpected_frames},
      {"hand_clamped_commands", s.clamped_commands}, {"hand_rejected_commands", s.rejected_commands},
      {"hand_safe_holds", s.safe_holds},   {"hand_fault_resets", s.fault_resets},
  };
  for (const auto& [name, value] : counters) report.counters.emplace_back(name, static_cast<double>(value));
}

}  // namespace teleop::hand
