#include "canopen_arm_bus.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace teleop::robot {

namespace cia402 = can::cia402;
namespace od = cia402::od;
using can::CanFrame;
using can::CanStatus;
using can::NodeId;

namespace {

constexpr uint32_t kPdoInvalid = 0x80000000u;
constexpr uint32_t kCia402Profile = 402;  // low word of the device type 0x1000
constexpr uint8_t kSynchronous = 1;       // transmission type: every SYNC

const can::PdoMapping& torque_rpdo() {
  static const can::PdoMapping m = *can::PdoMapping::make({{od::kControlword, 0, 16}, {od::kTargetTorque, 0, 16}});
  return m;
}
const can::PdoMapping& feedback_tpdo() {
  static const can::PdoMapping m = *can::PdoMapping::make(
      {{od::kPositionActualValue, 0, 32}, {od::kTorqueActualValue, 0, 16}, {od::kStatusword, 0, 16}});
  return m;
}

std::string percent(double fraction) {
  char text[16];
  std::snprintf(text, sizeof text, "%.1f %%", fraction * 100.0);
  return text;
}

void check(const CanopenBusConfig& config) {
  if (config.drives.empty()) throw std::invalid_argument("CANopen bus: no drives");
  std::array<bool, can::kMaxNodeId + 1> used{};
  if (!can::valid_node(config.master_node)) throw std::invalid_argument("CANopen bus: master_node must be 1..127");
  used[config.master_node] = true;
  for (const CanopenDriveConfig& d : config.drives) {
    if (!can::valid_node(d.node)) throw std::invalid_argument("CANopen bus: a drive's node id must be 1..127");
    if (used[d.node]) {
      throw std::invalid_argument("CANopen bus: node id " + std::to_string(d.node) + " is used twice (the master's " +
                                  std::to_string(config.master_node) + " counts)");
    }
    used[d.node] = true;
  }
  if (config.master_heartbeat_ms == 0 || config.drive_heartbeat_ms == 0) {
    throw std::invalid_argument("CANopen bus: heartbeat periods must be > 0 ms");
  }
  if (config.master_lost_after_ms <= config.master_heartbeat_ms || config.drive_lost_after_ms <= config.drive_heartbeat_ms) {
    throw std::invalid_argument("CANopen bus: a heartbeat is lost only after more than its period");
  }
  if (!(config.sync_period_s >= 1e-4 && config.sync_period_s <= 0.1) || !(config.bitrate_bps > 0)) {
    throw std::invalid_argument("CANopen bus: sync period in [0.1, 100] ms and a positive bitrate");
  }
  const can::BusLoad load = canopen_bus_load(config);
  if (load.exceeds()) {
    throw std::invalid_argument("CANopen bus: " + std::to_string(config.drives.size()) + " drives at " +
                                std::to_string(static_cast<int>(std::lround(1.0 / config.sync_period_s))) +
                                " Hz load the bus " + percent(load.load_worst_case) +
                                " in the worst case, above 70 %: fewer drives per bus, or a longer SYNC period "
                                "(docs/can_bus_budget.md)");
  }
}

}  // namespace

const char* to_string(BusFault fault) {
  switch (fault) {
    case BusFault::kNone: return "none";
    case BusFault::kEmcy: return "emergency";
    case BusFault::kHeartbeatLost: return "heartbeat lost";
    case BusFault::kDriveRebooted: return "drive rebooted";
    case BusFault::kBusOff: return "bus-off";
    case BusFault::kSendRefused: return "bus refused a frame";
  }
  return "?";
}

can::BusLoad canopen_bus_load(const CanopenBusConfig& config) {
  const auto drives = static_cast<uint32_t>(config.drives.size());
  const double sync_hz = 1.0 / config.sync_period_s;
  const std::array<can::Traffic, 5> traffic{{
      {1, 0, sync_hz},                                        // SYNC
      {drives, torque_rpdo().dlc(), sync_hz},                 // targets
      {drives, feedback_tpdo().dlc(), sync_hz},               // feedback
      {drives, 1, 1e3 / config.drive_heartbeat_ms},           // the drives' heartbeats
      {1, 1, 1e3 / config.master_heartbeat_ms},               // the master's
  }};
  return can::bus_load(traffic, config.bitrate_bps);
}

CanopenArmBus::CanopenArmBus(can::CanBus& bus, CanopenBusConfig config)
    : bus_(bus), config_(std::move(config)), rpdo_(torque_rpdo()), tpdo_(feedback_tpdo()) {
  check(config_);
  for (const CanopenDriveConfig& d : config_.drives) axes_.emplace_back(d.axis);
  commands_.resize(axes_.size());
  last_heartbeat_ns_.resize(axes_.size(), 0);
  feedback_seen_.resize(axes_.size(), 0);
}

int CanopenArmBus::index_of(NodeId node) const {
  for (size_t k = 0; k < config_.drives.size(); ++k) {
    if (config_.drives[k].node == node) return static_cast<int>(k);
  }
  return -1;
}

void CanopenArmBus::configure_drive(SdoClient& sdo, const CanopenDriveConfig& drive) {
  const NodeId n = drive.node;
  const uint32_t device_type = sdo.read(n, 0x1000, 0);
  if ((device_type & 0xFFFF) != kCia402Profile) {
    char text[16];
    std::snprintf(text, sizeof text, "0x%08X", device_type);
    throw std::runtime_error("drive " + std::to_string(n) + " is not a CiA 402 drive (device type " + text + ")");
  }
  const uint32_t rated_mnm = sdo.read(n, od::kMotorRatedTorque, 0);
  const double configured_mnm = drive.axis.rated_torque_nm * 1e3;
  if (std::fabs(rated_mnm - configured_mnm) > std::max(1.0, 0.005 * configured_mnm)) {
    throw std::runtime_error("drive " + std::to_string(n) + ": its rated torque 0x6076 is " + std::to_string(rated_mnm) +
                             " mN m, the configuration says " + std::to_string(configured_mnm) +
                             " mN m: the torque would be scaled wrong");
  }
  // a PDO's mapping changes only while it is not valid, its entries only while the count is 0
  auto map = [&](uint16_t communication, uint16_t mapping, uint32_t cob_id, const can::PdoMapping& entries) {
    sdo.write(n, communication, 1, kPdoInvalid | cob_id, 4);
    sdo.write(n, mapping, 0, 0, 1);
    for (size_t k = 0; k < entries.size(); ++k) sdo.write(n, mapping, static_cast<uint8_t>(k + 1), entries[k].to_u32(), 4);
    sdo.write(n, mapping, 0, static_cast<uint32_t>(entries.size()), 1);
    sdo.write(n, communication, 2, kSynchronous, 1);
    sdo.write(n, communication, 1, cob_id, 4);
  };
  map(0x1400, 0x1600, can::rpdo_cob_id(1, n), rpdo_);
  map(0x1800, 0x1A00, can::tpdo_cob_id(1, n), tpdo_);
  sdo.write(n, 0x1401, 1, kPdoInvalid | can::rpdo_cob_id(2, n), 4);  // nothing else on the bus
  sdo.write(n, 0x1801, 1, kPdoInvalid | can::tpdo_cob_id(2, n), 4);
  sdo.write(n, od::kModesOfOperation, 0, static_cast<uint8_t>(cia402::kModeCyclicSynchronousTorque), 1);
  // a quick stop brakes and stays in quick stop active: the master's hold, ended without power-off
  sdo.write(n, od::kQuickStopOptionCode, 0, static_cast<uint16_t>(cia402::kQuickStopRampAndHold), 2);
  sdo.write(n, can::obj::kProducerHeartbeatTime, 0, config_.drive_heartbeat_ms, 2);
  sdo.write(n, can::obj::kConsumerHeartbeatTime, 1,
            can::consumer_heartbeat_entry(config_.master_node, config_.master_lost_after_ms), 4);
  sdo.write(n, od::kAbortConnectionOptionCode, 0, static_cast<uint16_t>(config_.abort_connection_option), 2);
}

void CanopenArmBus::configure(const SdoWait& wait, int64_t now_ns) {
  started_ = false;
  fault_ = {};
  auto send_or_throw = [&](const can::Result<CanFrame>& frame, const char* what) {
    if (!frame.ok() || bus_.send(*frame) != CanStatus::kOk) throw std::runtime_error(std::string("CANopen: cannot send ") + what);
  };
  send_or_throw(can::encode_nmt(can::NmtCommand::kEnterPreOperational, 0), "NMT pre-operational");
  SdoClient sdo(bus_, wait);
  sdo.other_frames = [&](const CanFrame& frame) { take(frame, now_ns); };
  for (const CanopenDriveConfig& drive : config_.drives) configure_drive(sdo, drive);
  for (AxisCommand& c : commands_) c = {};
  for (Cia402Axis& a : axes_) a.reset();
  std::fill(feedback_seen_.begin(), feedback_seen_.end(), 0);
  send_or_throw(can::encode_nmt(can::NmtCommand::kStart, 0), "NMT start");
  started_ = true;
  watching_ = false;  // the watch of the drives' heartbeats starts with the first receive()
  next_heartbeat_ns_ = now_ns;
}

void CanopenArmBus::latch(BusFault fault, NodeId node, uint16_t emcy_code) {
  if (fault_.fault == BusFault::kNone) fault_ = {fault, node, emcy_code};
}

void CanopenArmBus::take(const CanFrame& frame, int64_t now_ns) {
  if (frame.error() || frame.extended() || frame.rtr()) return;
  const can::ServiceId service = can::classify(frame);
  const int k = index_of(service.node);
  if (k < 0) return;
  switch (service.service) {
    case can::Service::kTpdo: {
      if (service.pdo_number != 1) return;
      std::array<uint64_t, 3> v{};
      if (can::decode_pdo(frame, tpdo_, v) != can::CanError::kNone) return;
      const AxisFeedback feedback{static_cast<uint16_t>(v[2]), static_cast<int32_t>(can::sign_extend(v[0], 32)),
                                  static_cast<int16_t>(can::sign_extend(v[1], 16))};
      axes_[k].take(feedback, sampling_interval_s(feedback_seen_[k]));
      feedback_seen_[k] = stats_.syncs;
      ++stats_.tpdos;
      return;
    }
    case can::Service::kEmcy: {
      const auto emcy = can::decode_emcy(frame);
      if (!emcy.ok()) return;
      ++stats_.emcys;
      if (started_ && emcy->error_code != can::emcy::kErrorReset) latch(BusFault::kEmcy, service.node, emcy->error_code);
      return;
    }
    case can::Service::kHeartbeat: {
      const auto heartbeat = can::decode_heartbeat(frame);
      if (!heartbeat.ok()) return;
      if (started_ && heartbeat->state == can::NmtState::kBootUp) latch(BusFault::kDriveRebooted, service.node);
      last_heartbeat_ns_[k] = now_ns;
      return;
    }
    default:
      return;
  }
}

void CanopenArmBus::receive(int64_t now_ns) {
  CanFrame frame;
  while (bus_.receive(frame, std::chrono::nanoseconds::zero()) == CanStatus::kOk) take(frame, now_ns);
  if (bus_.state() == can::CanBusState::kBusOff) latch(BusFault::kBusOff, 0);
  if (!started_) return;
  if (!watching_) {
    std::fill(last_heartbeat_ns_.begin(), last_heartbeat_ns_.end(), now_ns);
    watching_ = true;
  }
  const int64_t lost_after_ns = int64_t{config_.drive_lost_after_ms} * 1'000'000;
  for (size_t k = 0; k < axes_.size(); ++k) {
    if (now_ns - last_heartbeat_ns_[k] > lost_after_ns) latch(BusFault::kHeartbeatLost, config_.drives[k].node);
  }
}

double CanopenArmBus::sampling_interval_s(uint64_t previous_sync) const {
  if (previous_sync == 0) return 0.0;
  const uint64_t periods = stats_.syncs - previous_sync;
  // the drives sample at the SYNC: the time between the two SYNCs as they were sent, which a
  // master that skipped cycles sent further apart than its period; older than the record: nominal
  if (periods >= sync_ns_.size()) return static_cast<double>(periods) * config_.sync_period_s;
  return static_cast<double>(sync_ns_[stats_.syncs % sync_ns_.size()] - sync_ns_[previous_sync % sync_ns_.size()]) * 1e-9;
}

int64_t CanopenArmBus::feedback_sampled_ns() const {
  const uint64_t oldest = *std::min_element(feedback_seen_.begin(), feedback_seen_.end());
  if (oldest == 0 || stats_.syncs - oldest >= sync_ns_.size()) return 0;
  return sync_ns_[oldest % sync_ns_.size()];
}

bool CanopenArmBus::feedback_complete() const {
  return std::all_of(feedback_seen_.begin(), feedback_seen_.end(), [&](uint64_t seen) { return seen == stats_.syncs; });
}

void CanopenArmBus::send(int64_t now_ns, bool heartbeat) {
  auto put = [&](const can::Result<CanFrame>& frame) {
    if (!frame.ok()) return;
    const CanStatus status = bus_.send(*frame);
    if (status == CanStatus::kOk) return;
    ++stats_.sends_refused;
    if (status == CanStatus::kBusOff) latch(BusFault::kBusOff, 0);
    if (status == CanStatus::kClosed || status == CanStatus::kIoError) latch(BusFault::kSendRefused, 0);
  };
  if (stats_.syncs > 0 && !feedback_complete()) ++stats_.incomplete_cycles;
  for (size_t k = 0; k < axes_.size(); ++k) {
    const std::array<uint64_t, 2> values{commands_[k].controlword, static_cast<uint16_t>(commands_[k].target_torque_permille)};
    put(can::encode_pdo(can::rpdo_cob_id(1, config_.drives[k].node), rpdo_, values));
  }
  put(can::encode_sync());
  ++stats_.syncs;
  sync_ns_[stats_.syncs % sync_ns_.size()] = now_ns;
  if (heartbeat && now_ns >= next_heartbeat_ns_) {
    put(can::encode_heartbeat(config_.master_node, can::NmtState::kOperational));
    next_heartbeat_ns_ = std::max(next_heartbeat_ns_ + int64_t{config_.master_heartbeat_ms} * 1'000'000, now_ns);
  }
}

}  // namespace teleop::robot
