// The hand adapter: its configuration, the phases of the cycle and the fault handling. The
// bus side (SDO client, reception, cyclic frames) is in hand_adapter_bus.cpp.
#include "teleop/hand/hand_adapter.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <stdexcept>

#include "teleop/can/cia402.h"

namespace teleop::hand {

namespace cia402 = can::cia402;
namespace od = can::cia402::od;
using can::CanBus;
using can::CanBusState;
using can::encode_nmt;
using can::kBusLoadWarnFraction;
using can::kMaxNodeId;
using can::NmtCommand;
using can::NodeId;
using can::valid_node;

namespace {

bool finite(const HandMotorVector& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

}  // namespace

const char* to_string(HandPhase phase) {
  switch (phase) {
    case HandPhase::kBooting:
      return "booting";
    case HandPhase::kConfiguring:
      return "configuring";
    case HandPhase::kEnabling:
      return "enabling";
    case HandPhase::kHoming:
      return "homing";
    case HandPhase::kOperational:
      return "operational";
    case HandPhase::kSafeHold:
      return "safe hold";
    case HandPhase::kFailed:
      return "failed";
  }
  return "?";
}

std::array<MotorChannelConfig, kHandMotors> HandAdapterConfig::default_channels() {
  std::array<MotorChannelConfig, kHandMotors> c{};
  for (auto& ch : c) {
    ch.ticks_per_rev = 4096.0;
    ch.gear_ratio = 100.0;
  }
  return c;
}

HandBusPlan hand_bus_plan(const HandAdapterConfig& config) {
  HandBusPlan plan;
  plan.motors = kHandMotors;
  plan.cycle_rate_hz = config.cycle_rate_hz;
  plan.bitrate_bps = config.bitrate_bps;
  plan.heartbeat_hz = config.heartbeat_ms > 0 ? 1000.0 / config.heartbeat_ms : 0.0;
  return plan;
}

std::optional<std::string> bus_load_warning(const HandAdapterConfig& config) {
  const HandBusBudget budget = hand_bus_budget(hand_bus_plan(config));
  if (!budget.load.exceeds()) return std::nullopt;
  char text[256];
  std::snprintf(text, sizeof text,
                "CAN bus load %.1f %% (worst case, %.1f %% nominal) at %.0f Hz on %.0f kbit/s exceeds %.0f %%; "
                "the highest rate within it is %.0f Hz",
                budget.load.load_worst_case * 100, budget.load.load_nominal * 100, config.cycle_rate_hz,
                config.bitrate_bps / 1e3, kBusLoadWarnFraction * 100, budget.max_cycle_rate_hz);
  return std::string(text);
}
// ---------------------------------------------------------------------------------------------
// setup

HandAdapter::HandAdapter(CanBus& bus, const HandAdapterConfig& config)
    : bus_(bus), config_(config), coupling_(HandCoupling::svh()), budget_(hand_bus_budget(hand_bus_plan(config))) {
  validate();
  period_s_ = 1.0 / config.cycle_rate_hz;
  motor_of_node_.fill(-1);
  drives_.reserve(kHandMotors);
  for (size_t m = 0; m < kHandMotors; ++m) {
    drives_.emplace_back(config.channels[m]);  // throws for an invalid channel
    drives_[m].node = config.node_ids[m];
    drives_[m].current_limit_a = config.default_current_limit_a;
    motor_of_node_[config.node_ids[m]] = static_cast<int8_t>(m);
    command_.position_rad[m] = std::clamp(0.0, config.min_position_rad[m], config.max_position_rad[m]);
  }
}

void HandAdapter::validate() const {
  const HandAdapterConfig& c = config_;
  std::array<bool, kMaxNodeId + 1> used{};
  for (size_t m = 0; m < kHandMotors; ++m) {
    const NodeId n = c.node_ids[m];
    if (!valid_node(n)) throw std::invalid_argument("hand adapter: node id " + std::to_string(n) + " not in 1..127");
    if (used[n]) throw std::invalid_argument("hand adapter: node id " + std::to_string(n) + " used twice");
    used[n] = true;
    if (!(c.min_position_rad[m] < c.max_position_rad[m]) || !std::isfinite(c.min_position_rad[m]) ||
        !std::isfinite(c.max_position_rad[m])) {
      throw std::invalid_argument("hand adapter: motor " + std::to_string(m) + ": need finite min < max position");
    }
    if (std::abs(c.homing.direction[m]) != 1) throw std::invalid_argument("hand adapter: homing direction must be +-1");
  }
  const HandGains& g = c.gains;
  for (double v : {g.position_kp_a_per_rad, g.position_ki_a_per_rad_s, g.position_kd_a_s_per_rad,
                   g.position_integral_limit_a, g.current_kp_v_per_a, g.current_ki_v_per_a_s}) {
    if (!(v >= 0) || !std::isfinite(v)) throw std::invalid_argument("hand adapter: gains must be finite and >= 0");
  }
  auto positive = [](double v) { return std::isfinite(v) && v > 0; };
  if (!positive(g.max_reference_velocity_radps) || !positive(c.cycle_rate_hz) || !positive(c.bitrate_bps) ||
      !positive(c.heartbeat_timeout_s) || !positive(c.boot_timeout_s) || !positive(c.sdo_timeout_s) ||
      !positive(c.enable_timeout_s) || c.pdo_timeout_cycles == 0 || c.heartbeat_ms == 0) {
    throw std::invalid_argument("hand adapter: rates, timeouts and the heartbeat must be positive");
  }
  if (c.heartbeat_timeout_s * 1e3 <= c.heartbeat_ms) {
    throw std::invalid_argument("hand adapter: heartbeat timeout must exceed the heartbeat period");
  }
  if (!(c.default_current_limit_a > 0) || !(c.max_current_limit_a >= c.default_current_limit_a) ||
      !std::isfinite(c.max_current_limit_a)) {
    throw std::invalid_argument("hand adapter: need 0 < default_current_limit_a <= max_current_limit_a");
  }
  if (c.homing.enabled &&
      (!positive(c.homing.velocity_radps) || !positive(c.homing.current_threshold_a) || !positive(c.homing.timeout_s) ||
       !finite(c.homing.stop_position_rad))) {
    throw std::invalid_argument("hand adapter: homing velocity, threshold and timeout must be positive");
  }
}
HandJointVector HandAdapter::joint_velocities() const {
  HandJointVector dq = coupling_.joints_from_motors(feedback_.velocity_radps);
  for (size_t j = 0; j < kHandJoints; ++j) dq[j] -= coupling_.offsets()[j];
  return dq;
}

// ---------------------------------------------------------------------------------------------
// commands

void HandAdapter::set_command(const HandTargets& targets) {
  commanded_ = true;
  if (!finite(targets.position_rad) || !finite(targets.current_limit_a)) {
    ++stats_.rejected_commands;
    command_.enable = targets.enable;
    command_.fault_reset = targets.fault_reset;
    return;
  }
  bool clamped = false;
  for (size_t m = 0; m < kHandMotors; ++m) {
    const double q = std::clamp(targets.position_rad[m], config_.min_position_rad[m], config_.max_position_rad[m]);
    const bool limited = q != targets.position_rad[m];
    clamped = clamped || limited;
    feedback_.faults[m] = limited ? feedback_.faults[m] | hand_fault::kLimit : feedback_.faults[m] & ~hand_fault::kLimit;
    command_.position_rad[m] = q;
    const double requested = targets.current_limit_a[m];
    const double current = std::clamp(requested, 0.0, config_.max_current_limit_a);
    clamped = clamped || current != requested;
    command_.current_limit_a[m] = current;
  }
  if (clamped) ++stats_.clamped_commands;
  command_.enable = targets.enable;
  command_.fault_reset = targets.fault_reset;
}

// ---------------------------------------------------------------------------------------------
// the cycle

void HandAdapter::cycle(int64_t now_ns) {
  ++stats_.cycles;
  last_now_ns_ = now_ns;
  receive_all(now_ns);
  switch (phase_) {
    case HandPhase::kBooting:
      boot(now_ns);
      return;
    case HandPhase::kConfiguring:
      configure(now_ns);
      return;
    case HandPhase::kFailed:
      return;
    default:
      break;
  }
  // the SYNC-driven phases
  update_feedback_faults();
  check_faults(now_ns);
  switch (phase_) {
    case HandPhase::kEnabling:
      enable(now_ns);
      break;
    case HandPhase::kHoming:
      home(now_ns);
      break;
    case HandPhase::kOperational:
      operate();
      break;
    case HandPhase::kSafeHold:
      hold();
      break;
    default:
      break;
  }
  if (phase_ == HandPhase::kFailed) return;
  pump_sdo(now_ns);
  send_cyclic();
}

void HandAdapter::enter(HandPhase phase, int64_t now_ns) {
  phase_ = phase;
  phase_start_ns_ = now_ns;
}

void HandAdapter::fail(const char* format, ...) {
  va_list args;
  va_start(args, format);
  std::vsnprintf(message_.data(), message_.size(), format, args);
  va_end(args);
  phase_ = HandPhase::kFailed;
}

void HandAdapter::boot(int64_t now_ns) {
  if (!boot_sent_) {
    // a known start: every node resets its communication objects and reports with a boot-up
    for (Drive& d : drives_) send(encode_nmt(NmtCommand::kResetCommunication, d.node));
    boot_sent_ = true;
    phase_start_ns_ = now_ns;
    return;
  }
  if (std::all_of(drives_.begin(), drives_.end(), [](const Drive& d) { return d.seen; })) {
    for (size_t m = 0; m < kHandMotors; ++m) queue_configuration(drives_[m], m);
    if (phase_ != HandPhase::kFailed) enter(HandPhase::kConfiguring, now_ns);
    return;
  }
  if (now_ns - phase_start_ns_ > static_cast<int64_t>(config_.boot_timeout_s * 1e9)) {
    for (size_t m = 0; m < kHandMotors; ++m) {
      if (drives_[m].seen) continue;
      fail("boot: no boot-up or heartbeat from node %u (%.*s) within %.0f ms", unsigned{drives_[m].node},
           static_cast<int>(kHandMotorNames[m].size()), kHandMotorNames[m].data(), config_.boot_timeout_s * 1e3);
      return;
    }
  }
}

void HandAdapter::configure(int64_t now_ns) {
  if (!pump_sdo(now_ns)) return;  // failed
  if (std::any_of(drives_.begin(), drives_.end(), [](const Drive& d) { return d.sdo_count > 0; })) return;
  for (Drive& d : drives_) {
    send(encode_nmt(NmtCommand::kStart, d.node));
    d.last_tpdo_cycle = stats_.cycles;
    d.last_heartbeat_ns = now_ns;
  }
  enter(HandPhase::kEnabling, now_ns);
}
void HandAdapter::enable(int64_t now_ns) {
  bool all_enabled = true;
  for (size_t m = 0; m < kHandMotors; ++m) {
    Drive& d = drives_[m];
    const uint16_t sw = feedback_.statusword[m];
    d.controlword = cia402::next_controlword(sw, d.controlword);
    d.hold_rad = feedback_.position_rad[m];
    all_enabled = all_enabled && d.have_feedback &&
                  cia402::state_from_statusword(sw) == cia402::State::kOperationEnabled;
  }
  if (all_enabled) {
    hold_actual_positions();
    const bool homing = config_.homing.enabled && !drives_[0].homed;
    if (!homing) {
      command_.position_rad = feedback_.target_rad;
      started_ = true;
    }
    enter(homing ? HandPhase::kHoming : HandPhase::kOperational, now_ns);
    return;
  }
  if (now_ns - phase_start_ns_ > static_cast<int64_t>(config_.enable_timeout_s * 1e9)) {
    for (size_t m = 0; m < kHandMotors; ++m) {
      const auto state = cia402::state_from_statusword(feedback_.statusword[m]);
      if (drives_[m].have_feedback && state == cia402::State::kOperationEnabled) continue;
      std::snprintf(message_.data(), message_.size(), "node %u did not reach operation enabled within %.0f ms (%s)",
                    unsigned{drives_[m].node}, config_.enable_timeout_s * 1e3,
                    drives_[m].have_feedback ? cia402::to_string(state) : "no TPDO");
      break;
    }
    enter_safe_hold(now_ns);
  }
}

void HandAdapter::home(int64_t now_ns) {
  const HandHomingConfig& h = config_.homing;
  bool all_homed = true;
  for (size_t m = 0; m < kHandMotors; ++m) {
    Drive& d = drives_[m];
    d.controlword = cia402::controlword_for(cia402::Command::kEnableOperation);
    if (d.homed) continue;
    all_homed = false;
    if (std::abs(feedback_.current_a[m]) >= h.current_threshold_a) {
      // at the hard stop: this tick count is stop_position_rad from now on
      MotorChannelConfig c = d.channel.config();
      c.offset_rad = 0.0;
      const MotorChannel unshifted(c);
      c.offset_rad = h.stop_position_rad[m] - unshifted.ticks_to_rad(d.position_ticks);
      d.channel = MotorChannel(c);
      feedback_.position_rad[m] = d.channel.ticks_to_rad(d.position_ticks);
      d.hold_rad = std::clamp(feedback_.position_rad[m], config_.min_position_rad[m], config_.max_position_rad[m]);
      d.homed = true;
      queue_limits(d, m);
      continue;
    }
    d.hold_rad += h.direction[m] * h.velocity_radps * period_s_;
  }
  if (all_homed && std::none_of(drives_.begin(), drives_.end(), [](const Drive& d) { return d.sdo_count > 0; })) {
    for (size_t m = 0; m < kHandMotors; ++m) command_.position_rad[m] = drives_[m].hold_rad;
    started_ = true;
    enter(HandPhase::kOperational, now_ns);
    return;
  }
  if (!all_homed && now_ns - phase_start_ns_ > static_cast<int64_t>(h.timeout_s * 1e9)) {
    for (size_t m = 0; m < kHandMotors; ++m) {
      if (drives_[m].homed) continue;
      fail("homing: node %u (%.*s) found no hard stop within %.1f s (current %.2f A, threshold %.2f A)",
           unsigned{drives_[m].node}, static_cast<int>(kHandMotorNames[m].size()), kHandMotorNames[m].data(),
           h.timeout_s, feedback_.current_a[m], h.current_threshold_a);
      return;
    }
  }
}

void HandAdapter::operate() {
  // until the first command arrives the hand holds where it is, enabled
  const bool enable = commanded_ ? command_.enable : true;
  const uint16_t cw =
      cia402::controlword_for(enable ? cia402::Command::kEnableOperation : cia402::Command::kQuickStop);
  for (size_t m = 0; m < kHandMotors; ++m) {
    Drive& d = drives_[m];
    d.controlword = cw;
    if (enable) d.hold_rad = command_.position_rad[m];
    // a changed current limit goes out by SDO
    const double limit = command_.current_limit_a[m] > 0 ? command_.current_limit_a[m] : config_.default_current_limit_a;
    if (limit != d.current_limit_a) {
      d.current_limit_a = limit;
      const auto permille = d.channel.amps_to_max_current_permille(limit);
      if (permille.ok()) queue_sdo(d, od::kMaxCurrent, 0, *permille, 2);
    }
  }
}

void HandAdapter::hold() {
  const bool reset = command_.fault_reset && !last_fault_reset_;
  last_fault_reset_ = command_.fault_reset;
  for (Drive& d : drives_) d.controlword = cia402::controlword_for(cia402::Command::kQuickStop);
  if (!reset) return;
  ++stats_.fault_resets;
  // clear what is over; what remains keeps the hand in safe hold
  const CanBusState bus = bus_.state();
  const bool bus_ok = bus == CanBusState::kErrorActive || bus == CanBusState::kErrorWarning;
  uint32_t remaining = 0;
  for (size_t m = 0; m < kHandMotors; ++m) {
    Drive& d = drives_[m];
    uint32_t keep = 0;
    if (!bus_ok) keep |= d.latched & (hand_fault::kBusOff | hand_fault::kBusPassive);
    if (last_now_ns_ - d.last_heartbeat_ns > static_cast<int64_t>(config_.heartbeat_timeout_s * 1e9)) {
      keep |= d.latched & hand_fault::kHeartbeat;
    }
    if (stats_.cycles - d.last_tpdo_cycle > config_.pdo_timeout_cycles) keep |= d.latched & hand_fault::kStalePdo;
    d.latched = keep;
    remaining |= keep;
    if (keep == 0) {
      feedback_.error_code[m] = 0;
      feedback_.sdo_abort_code[m] = 0;
      d.controlword = 0;  // the enable walk starts from here (fault reset edges included)
    }
  }
  if (remaining != 0) return;
  message_[0] = '\0';
  enter(HandPhase::kEnabling, last_now_ns_);
}

void HandAdapter::hold_actual_positions() {
  for (size_t m = 0; m < kHandMotors; ++m) {
    drives_[m].hold_rad = feedback_.position_rad[m];
    feedback_.target_rad[m] = feedback_.position_rad[m];
  }
}

void HandAdapter::enter_safe_hold(int64_t now_ns) {
  ++stats_.safe_holds;
  for (Drive& d : drives_) d.hold_rad = d.channel.ticks_to_rad(d.position_ticks);
  last_fault_reset_ = command_.fault_reset;  // a reset needs a new rising edge
  enter(HandPhase::kSafeHold, now_ns);
}

// ---------------------------------------------------------------------------------------------
// faults

void HandAdapter::update_feedback_faults() {
  for (size_t m = 0; m < kHandMotors; ++m) {
    const uint32_t momentary = feedback_.faults[m] & hand_fault::kLimit;
    const bool over = std::abs(feedback_.current_a[m]) > drives_[m].current_limit_a;
    feedback_.faults[m] = drives_[m].latched | momentary | (over ? hand_fault::kOverCurrent : 0);
  }
}

void HandAdapter::check_faults(int64_t now_ns) {
  const CanBusState bus = bus_.state();
  const uint32_t bus_fault = bus == CanBusState::kBusOff || bus == CanBusState::kDown ? hand_fault::kBusOff
                             : bus == CanBusState::kErrorPassive                      ? hand_fault::kBusPassive
                                                                                      : 0;
  bool new_fault = false;
  for (size_t m = 0; m < kHandMotors; ++m) {
    Drive& d = drives_[m];
    uint32_t f = bus_fault;
    if (now_ns - d.last_heartbeat_ns > static_cast<int64_t>(config_.heartbeat_timeout_s * 1e9)) f |= hand_fault::kHeartbeat;
    if (stats_.cycles - d.last_tpdo_cycle > config_.pdo_timeout_cycles) f |= hand_fault::kStalePdo;
    if (d.have_feedback && cia402::state_from_statusword(feedback_.statusword[m]) == cia402::State::kFault &&
        phase_ != HandPhase::kEnabling) {
      f |= hand_fault::kDrive;
    }
    const uint32_t added = (d.latched | f) & ~d.latched;
    d.latched |= f;
    // faults that arrived with a frame (EMCY, SDO, boot-up) are latched already: look at all
    if (added != 0 || (d.latched != 0 && phase_ != HandPhase::kSafeHold)) new_fault = true;
    feedback_.faults[m] |= d.latched;
  }
  if (!new_fault || phase_ == HandPhase::kSafeHold) return;
  for (size_t m = 0; m < kHandMotors; ++m) {
    if (drives_[m].latched == 0) continue;
    std::snprintf(message_.data(), message_.size(), "fault on node %u (%.*s): bits 0x%X, EMCY 0x%04X, SDO abort 0x%08X",
                  unsigned{drives_[m].node}, static_cast<int>(kHandMotorNames[m].size()), kHandMotorNames[m].data(),
                  drives_[m].latched, feedback_.error_code[m], feedback_.sdo_abort_code[m]);
    break;
  }
  enter_safe_hold(now_ns);
}
}  // namespace teleop::hand
