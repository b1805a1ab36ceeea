// The hand adapter's bus side: the SDO client that configures the drives (one write
// outstanding per node), the reception of every frame, and the frames sent each cycle
// (controlwords, SYNC, the targets packed two motors to a frame).
#include <algorithm>
#include <limits>
#include <span>

#include "teleop/can/cia402.h"
#include "teleop/hand/hand_adapter.h"
#include "teleop/drive/drive_objects.h"

namespace teleop::hand {

namespace cia402 = can::cia402;
namespace emcy = can::emcy;
namespace od = can::cia402::od;
namespace sdo_abort = can::sdo_abort;
using can::CanError;
using can::CanFrame;
using can::CanStatus;
using can::classify;
using can::decode_emcy;
using can::decode_heartbeat;
using can::decode_pdo;
using can::decode_sdo_response;
using can::encode_pdo;
using can::encode_sdo_download_request;
using can::encode_sync;
using can::kDummy32;
using can::kMaxNodeId;
using can::NmtState;
using can::PdoMapEntry;
using can::PdoMapping;
using can::Result;
using can::rpdo_cob_id;
using can::SdoType;
using can::Service;
using can::ServiceId;
using can::sign_extend;
using can::tpdo_cob_id;

namespace {

// frames read per cycle at most: a babbling node must not keep the cycle from ending
constexpr int kMaxFramesPerCycle = 512;
// sends of one SDO write while configuring before the adapter gives up (see pump_sdo)
constexpr uint8_t kSdoAttempts = 3;
// controlwords are sent on change; this often they are repeated in case one was lost
constexpr uint64_t kControlwordRefreshCycles = 25;
constexpr uint32_t kPdoDisabled = 0x80000000u;

const PdoMapping& feedback_mapping() {
  static const PdoMapping m = *PdoMapping::make({{od::kPositionActualValue, 0, 32},
                                                 {od::kCurrentActualValue, 0, 16},
                                                 {od::kStatusword, 0, 16}});
  return m;
}
const PdoMapping& controlword_mapping() {
  static const PdoMapping m = *PdoMapping::make({{od::kControlword, 0, 16}});
  return m;
}
// the frame of a pair's targets as the master packs it (each drive maps one half)
const PdoMapping& pair_mapping() {
  static const PdoMapping m = *PdoMapping::make({{od::kTargetPosition, 0, 32}, {od::kTargetPosition, 0, 32}});
  return m;
}
const PdoMapping& single_mapping() {
  static const PdoMapping m = *PdoMapping::make({{od::kTargetPosition, 0, 32}});
  return m;
}

constexpr PdoMapEntry kTargetEntry{od::kTargetPosition, 0, 32};

// motors are packed in pairs (0,1), (2,3), ...; the COB-ID is RPDO2 of the pair's first node
size_t pair_first(size_t motor) { return motor - motor % 2; }
}  // namespace

// ---------------------------------------------------------------------------------------------
// the SDO client

void HandAdapter::queue_sdo(Drive& d, uint16_t index, uint8_t subindex, uint32_t value, uint8_t size) {
  if (d.sdo_count == d.sdo.size()) {
    ++stats_.send_failures;  // never at the sizes used here; counted rather than overwritten
    return;
  }
  d.sdo[(d.sdo_head + d.sdo_count) % d.sdo.size()] = {index, subindex, size, value};
  ++d.sdo_count;
}

void HandAdapter::queue_configuration(Drive& d, size_t motor) {
  // TPDO1: position actual, current actual, statusword on every SYNC
  queue_sdo(d, 0x1800, 1, kPdoDisabled | tpdo_cob_id(1, d.node), 4);
  queue_sdo(d, 0x1A00, 0, 0, 1);
  for (size_t i = 0; i < feedback_mapping().size(); ++i) {
    queue_sdo(d, 0x1A00, static_cast<uint8_t>(i + 1), feedback_mapping()[i].to_u32(), 4);
  }
  queue_sdo(d, 0x1A00, 0, static_cast<uint32_t>(feedback_mapping().size()), 1);
  queue_sdo(d, 0x1800, 2, 1, 1);
  queue_sdo(d, 0x1800, 1, tpdo_cob_id(1, d.node), 4);
  // RPDO1: controlword alone, applied on reception
  queue_sdo(d, 0x1400, 1, kPdoDisabled | rpdo_cob_id(1, d.node), 4);
  queue_sdo(d, 0x1600, 0, 0, 1);
  queue_sdo(d, 0x1600, 1, controlword_mapping()[0].to_u32(), 4);
  queue_sdo(d, 0x1600, 0, 1, 1);
  queue_sdo(d, 0x1400, 2, 255, 1);
  queue_sdo(d, 0x1400, 1, rpdo_cob_id(1, d.node), 4);
  // RPDO2: the target, shared with the pair's other node (dummy mapping), applied at SYNC
  const size_t first = pair_first(motor);
  const bool paired = first + 1 < kHandMotors;
  const uint16_t cob = rpdo_cob_id(2, config_.node_ids[first]);
  queue_sdo(d, 0x1401, 1, kPdoDisabled | cob, 4);
  queue_sdo(d, 0x1601, 0, 0, 1);
  if (paired) {
    const bool second = motor != first;
    queue_sdo(d, 0x1601, 1, (second ? kDummy32 : kTargetEntry).to_u32(), 4);
    queue_sdo(d, 0x1601, 2, (second ? kTargetEntry : kDummy32).to_u32(), 4);
  } else {
    queue_sdo(d, 0x1601, 1, kTargetEntry.to_u32(), 4);
  }
  queue_sdo(d, 0x1601, 0, paired ? 2 : 1, 1);
  queue_sdo(d, 0x1401, 2, 1, 1);
  queue_sdo(d, 0x1401, 1, cob, 4);
  // drive: cyclic synchronous position, gains, current limit, limits, heartbeat
  queue_sdo(d, od::kModesOfOperation, 0, static_cast<uint8_t>(cia402::kModeCyclicSynchronousPosition), 1);
  const HandGains& g = config_.gains;
  const double gains[drive::drive_od::gain::kCount] = {g.position_kp_a_per_rad,      g.position_ki_a_per_rad_s,
                                               g.position_kd_a_s_per_rad,    g.position_integral_limit_a,
                                               g.max_reference_velocity_radps, g.current_kp_v_per_a,
                                               g.current_ki_v_per_a_s};
  for (uint8_t s = 1; s <= drive::drive_od::gain::kCount; ++s) {
    queue_sdo(d, drive::drive_od::kGains, s, drive::drive_od::real32_bits(gains[s - 1]), 4);
  }
  const auto permille = d.channel.amps_to_max_current_permille(d.current_limit_a);
  queue_sdo(d, od::kMaxCurrent, 0, permille.ok() ? *permille : 0, 2);
  if (config_.homing.enabled) {
    // open limits, so the drive can reach the hard stop; the real ones follow after homing
    queue_sdo(d, od::kSoftwarePositionLimit, 1, static_cast<uint32_t>(std::numeric_limits<int32_t>::min()), 4);
    queue_sdo(d, od::kSoftwarePositionLimit, 2, static_cast<uint32_t>(std::numeric_limits<int32_t>::max()), 4);
  } else {
    queue_limits(d, motor);
  }
  queue_sdo(d, 0x1017, 0, config_.heartbeat_ms, 2);
}

void HandAdapter::queue_limits(Drive& d, size_t motor) {
  const auto a = d.channel.rad_to_ticks(config_.min_position_rad[motor]);
  const auto b = d.channel.rad_to_ticks(config_.max_position_rad[motor]);
  if (!a.ok() || !b.ok()) {
    fail("node %u: software limits do not fit INTEGER32 ticks", unsigned{d.node});
    return;
  }
  queue_sdo(d, od::kSoftwarePositionLimit, 1, static_cast<uint32_t>(std::min(*a, *b)), 4);
  queue_sdo(d, od::kSoftwarePositionLimit, 2, static_cast<uint32_t>(std::max(*a, *b)), 4);
}
// Sends the next queued SDO write of every idle node and checks the outstanding ones for a
// timeout. False when the adapter failed (only while configuring: later an SDO problem is a fault).
bool HandAdapter::pump_sdo(int64_t now_ns) {
  for (size_t m = 0; m < kHandMotors; ++m) {
    Drive& d = drives_[m];
    if (d.sdo_busy && now_ns - d.sdo_sent_ns > static_cast<int64_t>(config_.sdo_timeout_s * 1e9)) {
      const SdoWrite& w = d.sdo[d.sdo_head];
      d.sdo_busy = false;
      // while configuring, a write is sent again before giving up: the first one after the
      // reset may reach a node that has not finished initialising (it ignores every frame then),
      // when its heartbeat from before the reset was taken for its boot
      if (phase_ == HandPhase::kConfiguring && d.sdo_attempts < kSdoAttempts) continue;
      d.sdo_head = (d.sdo_head + 1) % d.sdo.size();
      --d.sdo_count;
      d.sdo_attempts = 0;
      if (phase_ == HandPhase::kConfiguring) {
        fail("configuring node %u: no answer to SDO write 0x%04X:%u within %.0f ms (%u attempts)", unsigned{d.node},
             w.index, unsigned{w.subindex}, config_.sdo_timeout_s * 1e3, unsigned{kSdoAttempts});
        return false;
      }
      feedback_.sdo_abort_code[m] = sdo_abort::kTimeout;
      d.latched |= hand_fault::kSdo;
    }
    if (d.sdo_busy || d.sdo_count == 0) continue;
    const SdoWrite& w = d.sdo[d.sdo_head];
    send(encode_sdo_download_request(d.node, w.index, w.subindex, w.value, w.size));
    ++stats_.sdo_writes;
    ++d.sdo_attempts;
    d.sdo_busy = true;
    d.sdo_sent_ns = now_ns;
  }
  return phase_ != HandPhase::kFailed;
}
// ---------------------------------------------------------------------------------------------
// receive

void HandAdapter::receive_all(int64_t now_ns) {
  CanFrame frame;
  for (int i = 0; i < kMaxFramesPerCycle; ++i) {
    if (bus_.receive(frame, std::chrono::nanoseconds::zero()) != CanStatus::kOk) return;
    handle_frame(frame, now_ns);
  }
}

void HandAdapter::handle_frame(const CanFrame& frame, int64_t now_ns) {
  if (frame.error()) return;  // the bus state carries it (checked each cycle)
  const ServiceId id = classify(frame);
  const int motor = id.node <= kMaxNodeId ? motor_of_node_[id.node] : -1;
  if (motor < 0) return;  // not ours (or NMT / SYNC from another master)
  const auto m = static_cast<size_t>(motor);
  Drive& d = drives_[m];
  switch (id.service) {
    case Service::kTpdo:
      if (id.pdo_number == 1) handle_tpdo(d, m, frame);
      return;
    case Service::kHeartbeat: {
      const auto hb = decode_heartbeat(frame);
      if (!hb.ok()) break;
      // a node that boots again while running has lost its configuration
      if (hb->state == NmtState::kBootUp && phase_ >= HandPhase::kEnabling) d.latched |= hand_fault::kHeartbeat;
      d.seen = true;
      d.last_heartbeat_ns = now_ns;
      return;
    }
    case Service::kEmcy: {
      const auto e = decode_emcy(frame);
      if (!e.ok()) break;
      ++stats_.emcys;
      if (e->error_code == emcy::kErrorReset) return;
      feedback_.error_code[m] = e->error_code;
      if (phase_ >= HandPhase::kEnabling) d.latched |= hand_fault::kEmcy;
      return;
    }
    case Service::kSdoResponse:
      handle_sdo_response(d, m, frame);
      return;
    default:
      return;
  }
  ++stats_.unexpected_frames;
}

void HandAdapter::handle_tpdo(Drive& d, size_t m, const CanFrame& frame) {
  uint64_t v[3];
  if (decode_pdo(frame, feedback_mapping(), v) != CanError::kNone) {
    ++stats_.unexpected_frames;
    return;
  }
  ++stats_.tpdos_received;
  const double previous = feedback_.position_rad[m];
  d.position_ticks = static_cast<int32_t>(sign_extend(v[0], 32));
  feedback_.position_rad[m] = d.channel.ticks_to_rad(d.position_ticks);
  feedback_.current_a[m] = d.channel.permille_to_amps(static_cast<int16_t>(sign_extend(v[1], 16)));
  feedback_.statusword[m] = static_cast<uint16_t>(v[2]);
  // velocity from consecutive samples one cycle apart (the drive samples at SYNC)
  const uint64_t cycles = stats_.cycles - d.last_tpdo_cycle;
  feedback_.velocity_radps[m] =
      d.have_feedback && cycles > 0 ? (feedback_.position_rad[m] - previous) / (period_s_ * static_cast<double>(cycles))
                                    : 0.0;
  d.have_feedback = true;
  d.last_tpdo_cycle = stats_.cycles;
}

void HandAdapter::handle_sdo_response(Drive& d, size_t m, const CanFrame& frame) {
  const auto r = decode_sdo_response(frame);
  const SdoWrite& w = d.sdo[d.sdo_head];
  if (!r.ok() || !d.sdo_busy || r->index != w.index || r->subindex != w.subindex) {
    ++stats_.unexpected_frames;  // e.g. an answer to another client (cansend, a tool)
    return;
  }
  const bool aborted = r->type == SdoType::kAbort;
  d.sdo_busy = false;
  d.sdo_attempts = 0;
  d.sdo_head = (d.sdo_head + 1) % d.sdo.size();
  --d.sdo_count;
  if (!aborted) return;
  ++stats_.sdo_aborts;
  feedback_.sdo_abort_code[m] = r->abort_code;
  if (phase_ == HandPhase::kConfiguring) {
    fail("configuring node %u: SDO write 0x%04X:%u aborted with 0x%08X", unsigned{d.node}, r->index,
         unsigned{r->subindex}, r->abort_code);
    return;
  }
  d.latched |= hand_fault::kSdo;
}

// ---------------------------------------------------------------------------------------------
// send

void HandAdapter::send(const Result<CanFrame>& frame) {
  if (!frame.ok() || bus_.send(*frame) != CanStatus::kOk) ++stats_.send_failures;
}

void HandAdapter::send_cyclic() {
  // controlwords (RPDO1, applied on reception) before the SYNC that samples their effect
  const bool refresh = stats_.cycles % kControlwordRefreshCycles == 0;
  for (Drive& d : drives_) {
    if (d.controlword == d.sent_controlword && !refresh && phase_ != HandPhase::kEnabling) continue;
    const uint64_t cw = d.controlword;
    send(encode_pdo(rpdo_cob_id(1, d.node), controlword_mapping(), std::span<const uint64_t>(&cw, 1)));
    d.sent_controlword = d.controlword;
  }
  send(encode_sync());
  ++stats_.syncs_sent;
  // the targets for the next SYNC, two motors per frame
  for (size_t m = 0; m < kHandMotors; ++m) {
    Drive& d = drives_[m];
    const auto ticks = d.channel.rad_to_ticks(d.hold_rad);
    if (ticks.ok()) {
      d.target_ticks = *ticks;
      feedback_.target_rad[m] = d.hold_rad;
    }
  }
  for (size_t first = 0; first < kHandMotors; first += 2) {
    const uint16_t cob = rpdo_cob_id(2, drives_[first].node);
    if (first + 1 < kHandMotors) {
      const uint64_t v[2] = {static_cast<uint32_t>(drives_[first].target_ticks),
                             static_cast<uint32_t>(drives_[first + 1].target_ticks)};
      send(encode_pdo(cob, pair_mapping(), v));
    } else {
      const uint64_t v = static_cast<uint32_t>(drives_[first].target_ticks);
      send(encode_pdo(cob, single_mapping(), std::span<const uint64_t>(&v, 1)));
    }
    ++stats_.rpdos_sent;
  }
}
}  // namespace teleop::hand
