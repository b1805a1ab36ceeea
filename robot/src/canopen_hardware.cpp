#include "canopen_hardware.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <thread>

namespace teleop::robot {

std::vector<std::string> CanopenHardware::interfaces(const CanopenHardwareConfig& config) {
  std::vector<std::string> names;
  for (const CanopenJointConfig& j : config.joints) {
    if (std::find(names.begin(), names.end(), j.bus) == names.end()) names.push_back(j.bus);
  }
  return names;
}

CanopenBusConfig canopen_bus_config(const CanopenHardwareConfig& config, const std::string& interface, double sync_period_s) {
  CanopenBusConfig bus;
  for (const CanopenJointConfig& j : config.joints) {
    if (j.bus == interface) bus.drives.push_back({j.node, j.axis});
  }
  bus.master_node = config.master_node;
  bus.master_heartbeat_ms = config.master_heartbeat_ms;
  bus.drive_heartbeat_ms = config.drive_heartbeat_ms;
  bus.master_lost_after_ms = config.master_lost_after_ms;
  bus.drive_lost_after_ms = config.drive_lost_after_ms;
  bus.sync_period_s = sync_period_s;
  bus.bitrate_bps = config.bitrate_bps;
  return bus;
}

CanopenHardware::CanopenHardware(const CanopenHardwareConfig& config, double period_s, std::vector<can::CanBus*> buses,
                                 const SdoWait& wait, Clock clock, std::vector<std::unique_ptr<can::CanBus>> owned)
    : config_(config), owned_(std::move(owned)), clock_(std::move(clock)), name_("canopen:") {
  const std::vector<std::string> names = interfaces(config);
  if (buses.size() != names.size()) throw std::invalid_argument("CANopen hardware: one bus per interface");
  for (size_t b = 0; b < names.size(); ++b) {
    name_ += (b == 0 ? "" : ",") + names[b];
    try {
      buses_.push_back(std::make_unique<CanopenArmBus>(*buses[b], canopen_bus_config(config, names[b], period_s * config.sync_divider)));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(names[b] + ": " + e.what());
    }
  }
  std::vector<size_t> next(names.size(), 0);
  for (const CanopenJointConfig& j : config.joints) {
    const size_t b = static_cast<size_t>(std::find(names.begin(), names.end(), j.bus) - names.begin());
    joints_.push_back({b, next[b]++});
  }
  start(wait);
}

CanopenHardware::~CanopenHardware() {
  // the drives hold by their quick stop; once the master's heartbeat stops they would anyway
  (void)hold();
}

template <typename Command>
void CanopenHardware::start_cycle(const SdoWait& wait, Command command) {
  const int64_t now = clock_();
  for (auto& bus : buses_) bus->receive(now);
  for (const Joint& j : joints_) buses_[j.bus]->command(j.axis, command(axis(j)));
  for (auto& bus : buses_) bus->send(now, false);  // no heartbeat yet (CanopenArmBus::send)
  if (wait.pump) {
    wait.pump();
  } else {
    std::this_thread::sleep_for(wait.poll);
  }
}

// configure every bus, walk every drive to operation enabled at zero torque, then into the quick
// stop it holds in until the follower's first command (a few cycles at zero torque in between:
// an arm under gravity sags by a fraction of a millimetre)
void CanopenHardware::start(const SdoWait& wait) {
  for (size_t b = 0; b < buses_.size(); ++b) {
    try {
      buses_[b]->configure(wait, clock_());
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(name_ + ": " + e.what());
    }
  }
  const auto cycles = static_cast<int>(config_.enable_timeout_s / std::chrono::duration<double>(wait.poll).count());
  auto all = [&](auto predicate) {
    return std::all_of(joints_.begin(), joints_.end(), [&](const Joint& j) { return predicate(axis(j)); });
  };
  auto fault = [&]() -> std::string {
    for (size_t b = 0; b < buses_.size(); ++b) {
      const BusFaultInfo& f = buses_[b]->fault();
      if (f.fault != BusFault::kNone) return std::string(to_string(f.fault)) + " of node " + std::to_string(f.node);
    }
    return "";
  };
  for (int i = 0; i < cycles && !all([](const Cia402Axis& a) { return a.enabled(); }); ++i) {
    start_cycle(wait, [](Cia402Axis& a) { return a.command(0.0); });
  }
  for (int i = 0; i < cycles && !all([](const Cia402Axis& a) { return a.holding(); }); ++i) {
    start_cycle(wait, [](Cia402Axis& a) { return a.enabled() || a.holding() ? a.quick_stop() : a.command(0.0); });
  }
  if (!all([](const Cia402Axis& a) { return a.holding(); }) || !fault().empty()) {
    std::string which;
    for (size_t k = 0; k < joints_.size(); ++k) {
      const Cia402Axis& a = axis(joints_[k]);
      if (!a.holding()) {
        which += " joint " + std::to_string(k + 1) + " (node " + std::to_string(config_.joints[k].node) + ") is " +
                 can::cia402::to_string(a.state()) + ";";
      }
    }
    throw std::runtime_error(name_ + ": the drives did not reach their holding quick stop within " +
                             std::to_string(config_.enable_timeout_s) + " s:" + which + " " + fault());
  }
}

HardwareStatus CanopenHardware::read(ArmState& state) {
  const int64_t now = clock_();
  bool failed = false;
  int64_t sampled_ns = std::numeric_limits<int64_t>::max();
  for (auto& bus : buses_) {
    bus->receive(now);
    failed = failed || bus->fault().fault != BusFault::kNone;
    sampled_ns = std::min(sampled_ns, bus->feedback_sampled_ns());
  }
  for (size_t k = 0; k < joints_.size(); ++k) {
    const Cia402Axis& a = axis(joints_[k]);
    state.q_rad[k] = a.position_rad();
    state.dq_radps[k] = a.velocity_radps();
    state.tau_measured_nm[k] = a.torque_nm();
    failed = failed || a.failed();
  }
  state.tau_ext_nm = JointVector{};  // the drives measure none: the follower's observer estimates it
  state.wrench_measured = false;
  state.measured_ns = sampled_ns;
  failed_ = failed_ || failed;
  if (failed_) return HardwareStatus::kFault;
  const bool fresh = sampled_ns > 0 && static_cast<double>(now - sampled_ns) * 1e-9 <= config_.state_timeout_s;
  return fresh ? HardwareStatus::kOk : HardwareStatus::kStale;
}

void CanopenHardware::send_all() {
  // with a divider, the commands of the cycles between two SYNCs replace each other
  if (cycle_++ % config_.sync_divider != 0) return;
  const int64_t now = clock_();
  for (auto& bus : buses_) bus->send(now);
}

HardwareStatus CanopenHardware::write(const JointVector& tau_nm) {
  // one drive failed: the arm is no longer the arm the torques were computed for; all hold
  if (failed_) return hold();
  for (size_t k = 0; k < joints_.size(); ++k) buses_[joints_[k].bus]->command(joints_[k].axis, axis(joints_[k]).command(tau_nm[k]));
  send_all();
  return HardwareStatus::kOk;
}

HardwareStatus CanopenHardware::hold() {
  for (const Joint& j : joints_) buses_[j.bus]->command(j.axis, axis(j).quick_stop());
  send_all();
  return HardwareStatus::kOk;
}

HardwareLimits CanopenHardware::limits() const {
  HardwareLimits limits;
  constexpr double inf = std::numeric_limits<double>::infinity();
  limits.q_min_rad.fill(-inf);
  limits.q_max_rad.fill(inf);
  limits.max_torque_nm.fill(inf);
  for (size_t k = 0; k < config_.joints.size(); ++k) {
    limits.q_min_rad[k] = config_.joints[k].q_min_rad;
    limits.q_max_rad[k] = config_.joints[k].q_max_rad;
    limits.max_torque_nm[k] = config_.joints[k].axis.max_torque_nm;
  }
  return limits;
}

void CanopenHardware::report_counters(std::vector<std::pair<std::string, double>>& counters) const {
  double clamped = 0, incomplete = 0, emcys = 0, refused = 0, fault = 0, fault_node = 0, fault_emcy = 0;
  for (const auto& bus : buses_) {
    for (size_t k = 0; k < bus->size(); ++k) clamped += static_cast<double>(bus->axis(k).clamped_commands());
    incomplete += static_cast<double>(bus->stats().incomplete_cycles);
    emcys += static_cast<double>(bus->stats().emcys);
    refused += static_cast<double>(bus->stats().sends_refused);
    if (fault == 0 && bus->fault().fault != BusFault::kNone) {
      fault = static_cast<double>(bus->fault().fault);
      fault_node = bus->fault().node;
      fault_emcy = bus->fault().emcy_code;
    }
  }
  counters.emplace_back("canopen_torques_clamped", clamped);
  counters.emplace_back("canopen_cycles_feedback_missing", incomplete);
  counters.emplace_back("canopen_emcys", emcys);
  counters.emplace_back("canopen_frames_refused", refused);
  // which BusFault (1 EMCY, 2 heartbeat lost, 3 drive rebooted, 4 bus-off, 5 send refused), of which node
  counters.emplace_back("canopen_fault", fault);
  counters.emplace_back("canopen_fault_node", fault_node);
  counters.emplace_back("canopen_fault_emcy_code", fault_emcy);
}

}  // namespace teleop::robot
