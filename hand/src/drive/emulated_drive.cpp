#include "teleop/hand/emulated_drive.h"

#include "teleop/hand/hand_drive_objects.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>

namespace teleop::hand {

namespace cia402 = can::cia402;
namespace cob = can::cob;
namespace emcy = can::emcy;
namespace le = can::le;
namespace od = can::cia402::od;
namespace sdo_abort = can::sdo_abort;
using can::CanBus;
using can::CanError;
using can::CanFrame;
using can::CanStatus;
using can::decode_nmt;
using can::decode_pdo;
using can::decode_sdo_request;
using can::decode_sync;
using can::EmcyMessage;
using can::encode_emcy;
using can::encode_heartbeat;
using can::encode_pdo;
using can::encode_sdo_abort;
using can::encode_sdo_download_response;
using can::encode_sdo_upload_response;
using can::error_register_for;
using can::NmtCommand;
using can::NmtMessage;
using can::NmtState;
using can::NodeId;
using can::PdoMapEntry;
using can::PdoMapping;
using can::rpdo_cob_id;
using can::SdoType;
using can::tpdo_cob_id;
using can::valid_node;
using cia402::State;

namespace {

// one entry of the drive's object dictionary (objects other than the PDO parameters)
struct ObjectEntry {
  uint16_t index;
  uint8_t subindex;
  uint8_t bits;
  bool writable;
  bool rx_mappable;
  bool tx_mappable;
};

constexpr ObjectEntry kObjects[] = {
    {0x1000, 0, 32, false, false, false},  // device type
    {0x1001, 0, 8, false, false, true},    // error register
    {0x1017, 0, 16, true, false, false},   // producer heartbeat time [ms]
    {0x1018, 0, 8, false, false, false},   // identity: highest subindex
    {0x1018, 1, 32, false, false, false},  // vendor id
    {0x1018, 2, 32, false, false, false},  // product code
    {0x1018, 3, 32, false, false, false},  // revision
    {0x1018, 4, 32, false, false, false},  // serial number
    {od::kErrorCode, 0, 16, false, false, true},
    {od::kControlword, 0, 16, true, true, false},
    {od::kStatusword, 0, 16, false, false, true},
    {od::kModesOfOperation, 0, 8, true, true, false},
    {od::kModesOfOperationDisplay, 0, 8, false, false, true},
    {od::kPositionActualValue, 0, 32, false, false, true},
    {od::kFollowingErrorWindow, 0, 32, true, false, false},
    {od::kFollowingErrorTimeout, 0, 16, true, false, false},
    {od::kVelocityActualValue, 0, 32, false, false, true},
    {od::kMaxCurrent, 0, 16, true, true, false},
    {od::kMotorRatedCurrent, 0, 32, false, false, false},
    {od::kTorqueActualValue, 0, 16, false, false, true},
    {od::kCurrentActualValue, 0, 16, false, false, true},
    {od::kTargetPosition, 0, 32, true, true, false},
    {od::kSoftwarePositionLimit, 0, 8, false, false, false},
    {od::kSoftwarePositionLimit, 1, 32, true, false, false},
    {od::kSoftwarePositionLimit, 2, 32, true, false, false},
    // manufacturer objects (hand_drive_objects.h): gains, fault injection
    {hand_od::kGains, 0, 8, false, false, false},
    {hand_od::kGains, 1, 32, true, false, false},
    {hand_od::kGains, 2, 32, true, false, false},
    {hand_od::kGains, 3, 32, true, false, false},
    {hand_od::kGains, 4, 32, true, false, false},
    {hand_od::kGains, 5, 32, true, false, false},
    {hand_od::kGains, 6, 32, true, false, false},
    {hand_od::kGains, 7, 32, true, false, false},
    {hand_od::kFaultInjection, 0, 8, false, false, false},
    {hand_od::kFaultInjection, 1, 32, true, false, false},
    {hand_od::kFaultInjection, 2, 32, true, false, false},
    {hand_od::kFaultInjection, 3, 32, true, false, false},
    {hand_od::kFaultInjection, 4, 32, true, false, false},
    {hand_od::kFaultInjection, 5, 32, true, false, false},
    {hand_od::kFaultInjection, 6, 32, true, false, false},
};

constexpr uint32_t kPdoInvalid = 0x80000000u;
constexpr uint32_t kPdoExtendedId = 0x20000000u;
constexpr uint32_t kFollowingErrorOff = 0xFFFFFFFFu;

// length in bits of the data-type "objects" 0x0001..0x0007 used as dummy mapping entries
uint8_t dummy_bits(uint16_t index) {
  switch (index) {
    case 0x0001:
      return 1;
    case 0x0002:
      return 8;
    case 0x0003:
      return 16;
    case 0x0004:
      return 32;
    case 0x0005:
      return 8;
    case 0x0006:
      return 16;
    case 0x0007:
      return 32;
    default:
      return 0;
  }
}

bool valid_transmission_type(uint32_t type) { return type <= 240 || type == 254 || type == 255; }

// COB-IDs CiA 301 reserves for NMT, SDO, NMT error control and LSS, plus SYNC (0x080), which
// this drive would otherwise take for a PDO
bool restricted_cob_id(uint32_t id) {
  return id <= 0x080 || (id >= 0x101 && id <= 0x180) || (id >= 0x581 && id <= 0x5FF) || (id >= 0x601 && id <= 0x67F) ||
         (id >= 0x6E0 && id <= 0x6FF) || id >= 0x701;
}

bool positive_finite(double v) { return std::isfinite(v) && v > 0; }

int32_t saturate_int32(double v) {
  if (!(v > static_cast<double>(std::numeric_limits<int32_t>::min()))) return std::numeric_limits<int32_t>::min();
  if (!(v < static_cast<double>(std::numeric_limits<int32_t>::max()))) return std::numeric_limits<int32_t>::max();
  return static_cast<int32_t>(std::lround(v));
}

int16_t saturate_int16(double v) {
  if (!(v > -32768.0)) return -32768;
  if (!(v < 32767.0)) return 32767;
  return static_cast<int16_t>(std::lround(v));
}

uint32_t mask_to_bits(uint32_t value, unsigned bits) { return bits >= 32 ? value : value & ((1u << bits) - 1); }

// the controller parameter behind a subindex of the gains object (nullptr: no such subindex);
// Params is EmulatedControllerParams, const or not
template <typename Params>
auto gain_slot(Params& c, uint8_t subindex) -> decltype(&c.position_kp_a_per_rad) {
  switch (subindex) {
    case hand_od::gain::kPositionKp:
      return &c.position_kp_a_per_rad;
    case hand_od::gain::kPositionKi:
      return &c.position_ki_a_per_rad_s;
    case hand_od::gain::kPositionKd:
      return &c.position_kd_a_s_per_rad;
    case hand_od::gain::kIntegralLimit:
      return &c.position_integral_limit_a;
    case hand_od::gain::kMaxReferenceVelocity:
      return &c.max_reference_velocity_radps;
    case hand_od::gain::kCurrentKp:
      return &c.current_kp_v_per_a;
    case hand_od::gain::kCurrentKi:
      return &c.current_ki_v_per_a_s;
    default:
      return nullptr;
  }
}

}  // namespace

struct EmulatedDrive::ObjectInfo {
  uint8_t bits = 0;
  bool writable = false;
  bool rx_mappable = false;
  bool tx_mappable = false;
};

// ---------------------------------------------------------------------------------------------
// setup

EmulatedDrive::EmulatedDrive(CanBus& bus, const EmulatedDriveConfig& config) : bus_(bus), config_(config) {
  const EmulatedMotorParams& m = config.motor;
  const EmulatedControllerParams& c = config.control;
  if (!valid_node(config.node_id)) {
    throw std::invalid_argument("EmulatedDrive: node id " + std::to_string(config.node_id) + " is not in 1..127");
  }
  if (!positive_finite(m.supply_v) || !positive_finite(m.resistance_ohm) || !positive_finite(m.inductance_h) ||
      !positive_finite(m.torque_constant_nm_per_a) || !positive_finite(m.rotor_inertia_kgm2) ||
      !positive_finite(m.gear_ratio) || !positive_finite(m.gear_efficiency) || !positive_finite(m.link_inertia_kgm2) ||
      !positive_finite(m.encoder_ticks_per_rev) || !(m.viscous_nms_per_rad >= 0) ||
      !(m.stop_stiffness_nm_per_rad >= 0) || !(m.stop_damping_nms_per_rad >= 0)) {
    throw std::invalid_argument("EmulatedDrive: motor parameters must be positive and finite");
  }
  if (!(m.stop_min_rad < m.stop_max_rad)) throw std::invalid_argument("EmulatedDrive: stop_min_rad >= stop_max_rad");
  if (!(config.initial_position_rad >= m.stop_min_rad && config.initial_position_rad <= m.stop_max_rad)) {
    throw std::invalid_argument("EmulatedDrive: initial_position_rad outside the hard stops");
  }
  if (!positive_finite(c.substep_s) || c.substep_s > 1e-3 || c.position_loop_divider == 0) {
    throw std::invalid_argument("EmulatedDrive: substep_s must be in (0, 1 ms], position_loop_divider >= 1");
  }
  if (!positive_finite(c.max_reference_velocity_radps) || !positive_finite(c.velocity_filter_hz) ||
      !(c.position_kp_a_per_rad >= 0) || !(c.position_ki_a_per_rad_s >= 0) || !(c.position_kd_a_s_per_rad >= 0) ||
      !(c.position_integral_limit_a >= 0) || !(c.current_kp_v_per_a >= 0) || !(c.current_ki_v_per_a_s >= 0)) {
    throw std::invalid_argument("EmulatedDrive: controller gains must be finite and >= 0");
  }
  if (!positive_finite(config.rated_current_a) || !positive_finite(config.peak_current_a) ||
      !(config.max_current_a >= 0) || config.max_current_a > config.peak_current_a) {
    throw std::invalid_argument("EmulatedDrive: need rated, peak > 0 and 0 <= max_current_a <= peak_current_a");
  }
  if (!(config.following_error_window_rad > 0) || !(config.fault_reaction_time_s >= 0)) {
    throw std::invalid_argument("EmulatedDrive: following_error_window_rad > 0, fault_reaction_time_s >= 0");
  }

  ticks_per_rad_ = m.encoder_ticks_per_rev * m.gear_ratio / (2.0 * M_PI);
  substep_ns_ = std::max<int64_t>(1, std::llround(c.substep_s * 1e9));
  const double position_period_s = c.substep_s * c.position_loop_divider;
  velocity_filter_alpha_ = 1.0 - std::exp(-2.0 * M_PI * c.velocity_filter_hz * position_period_s);
  current_decay_ = std::exp(-c.substep_s * m.resistance_ohm / m.inductance_h);

  q_rad_ = config.initial_position_rad;
  q_meas_prev_rad_ = position_ticks() / ticks_per_rad_;
  reset_application();
  reset_communication();
}

void EmulatedDrive::reset_application() {
  error_register_ = 0;
  error_code_ = 0;
  controlword_ = 0;
  mode_ = cia402::kModeNone;
  target_ticks_ = 0;
  const double window_ticks = config_.following_error_window_rad * ticks_per_rad_;
  following_error_window_ticks_ = window_ticks >= static_cast<double>(kFollowingErrorOff)
                                      ? kFollowingErrorOff
                                      : static_cast<uint32_t>(window_ticks);
  following_error_timeout_ms_ = config_.following_error_timeout_ms;
  max_current_permille_ = static_cast<uint16_t>(std::lround(config_.max_current_a / config_.rated_current_a * 1e3));
  limit_min_ticks_ = std::numeric_limits<int32_t>::min();
  limit_max_ticks_ = std::numeric_limits<int32_t>::max();
  state_ = State::kNotReadyToSwitchOn;
  fault_reaction_remaining_ns_ = 0;
  internal_limit_ = false;
  following_error_ = false;
  following_error_ns_ = 0;
  ref_rad_ = position_ticks() / ticks_per_rad_;
  ref_velocity_radps_ = 0;
  position_integral_a_ = 0;
  current_ref_a_ = 0;
  current_integral_v_ = 0;
}

void EmulatedDrive::reset_communication() {
  const NodeId id = config_.node_id;
  heartbeat_ms_ = config_.heartbeat_ms;
  rpdo_ = {};
  tpdo_ = {};
  // PDO1s valid, PDO2s prepared but not valid
  rpdo_[0].cob_id = rpdo_cob_id(1, id);
  rpdo_[0].map_raw = {0x60400010, 0x607A0020};
  rpdo_[0].map_count = 2;
  rpdo_[1].cob_id = kPdoInvalid | rpdo_cob_id(2, id);
  tpdo_[0].cob_id = tpdo_cob_id(1, id);
  tpdo_[0].map_raw = {0x60640020, 0x60780010, 0x60410010};
  tpdo_[0].map_count = 3;
  tpdo_[1].cob_id = kPdoInvalid | tpdo_cob_id(2, id);
  tpdo_[1].map_raw = {0x606C0020, 0x603F0010};
  tpdo_[1].map_count = 2;
  for (PdoChannel* pdo : {&rpdo_[0], &rpdo_[1], &tpdo_[0], &tpdo_[1]}) {
    pdo->transmission_type = 1;
    for (uint8_t i = 0; i < pdo->map_count; ++i) {
      (void)pdo->mapping.add(PdoMapEntry::from_u32(pdo->map_raw[i]));  // known-good defaults
    }
  }
  delayed_count_ = 0;
}

// ---------------------------------------------------------------------------------------------
// the step

void EmulatedDrive::step(double dt_s) {
  if (!(dt_s >= 0) || !std::isfinite(dt_s)) return;

  // the frames on the bus at the current time
  CanFrame frame;
  while (bus_.receive(frame, std::chrono::nanoseconds::zero()) == CanStatus::kOk) handle_frame(frame);

  // initialisation ends with the boot-up message (after power-on and after every reset)
  if (initialising_) {
    initialising_ = false;
    nmt_ = NmtState::kPreOperational;
    if (const auto boot = encode_heartbeat(config_.node_id, NmtState::kBootUp); boot.ok()) send(*boot);
    next_heartbeat_ns_ = now_ns_ + int64_t{heartbeat_ms_} * 1'000'000;
    if (state_ == State::kNotReadyToSwitchOn) enter_state(State::kSwitchOnDisabled);  // transition 1
  }

  // the controlword is level-triggered (only fault reset needs an edge, seen on write)
  evaluate_controlword(controlword_);

  // physics and control
  pending_ns_ += std::llround(dt_s * 1e9);
  while (pending_ns_ >= substep_ns_) {
    substep();
    pending_ns_ -= substep_ns_;
  }
  now_ns_ += std::llround(dt_s * 1e9);

  service_timers();
}

void EmulatedDrive::service_timers() {
  // heartbeat producer
  const bool producing = !initialising_ && heartbeat_ms_ > 0;
  if (producing && now_ns_ >= next_heartbeat_ns_) {
    if (!heartbeat_suppressed_) {
      if (const auto hb = encode_heartbeat(config_.node_id, nmt_); hb.ok()) {
        send(*hb);
        ++stats_.heartbeats_sent;
      }
    }
    const int64_t period_ns = int64_t{heartbeat_ms_} * 1'000'000;
    next_heartbeat_ns_ += period_ns;
    if (next_heartbeat_ns_ <= now_ns_) next_heartbeat_ns_ = now_ns_ + period_ns;  // after a long step
  }

  // event-driven TPDOs (transmission type 254/255) on their event timer
  if (nmt_ == NmtState::kOperational) {
    for (PdoChannel& pdo : tpdo_) {
      if (!pdo.valid() || pdo.transmission_type < 254 || pdo.event_timer_ms == 0) continue;
      if (now_ns_ >= pdo.next_event_ns) {
        send_tpdo(pdo);
        const int64_t period_ns = int64_t{pdo.event_timer_ms} * 1'000'000;
        pdo.next_event_ns += period_ns;
        if (pdo.next_event_ns <= now_ns_) pdo.next_event_ns = now_ns_ + period_ns;
      }
    }
  }

  // delayed TPDOs whose time has come, oldest first
  size_t kept = 0;
  for (size_t i = 0; i < delayed_count_; ++i) {
    if (delayed_[i].release_ns <= now_ns_) {
      send(delayed_[i].frame);
      ++stats_.tpdos_sent;
    } else {
      delayed_[kept++] = delayed_[i];
    }
  }
  delayed_count_ = kept;
}

// ---------------------------------------------------------------------------------------------
// frames

void EmulatedDrive::send(const CanFrame& frame) {
  if (bus_.send(frame) == CanStatus::kOk) {
    ++stats_.frames_sent;
  } else {
    ++stats_.send_failures;
  }
}

void EmulatedDrive::handle_frame(const CanFrame& frame) {
  ++stats_.frames_received;
  if (frame.error()) return;  // the controller's own business
  if (initialising_) return;  // a node in initialisation takes part in nothing
  const NodeId id = config_.node_id;

  // PDOs first: their COB-IDs are configurable and may be anything but the ids below
  if (nmt_ == NmtState::kOperational && !frame.extended() && !frame.rtr()) {
    for (PdoChannel& pdo : rpdo_) {
      if (pdo.valid() && (pdo.cob_id & CanFrame::kMaxStandardId) == frame.id) {
        handle_rpdo(pdo, frame);
        return;
      }
    }
  }

  if (frame.id == cob::kNmt && !frame.extended()) {
    const auto nmt = decode_nmt(frame);
    if (!nmt.ok()) {
      ++stats_.malformed_frames;
      return;
    }
    if (nmt->node == 0 || nmt->node == id) handle_nmt(*nmt);
    return;
  }
  if (frame.id == cob::kSync && !frame.extended()) {
    if (decode_sync(frame).ok()) {
      handle_sync();
    } else {
      ++stats_.malformed_frames;
    }
    return;
  }
  if (frame.id == static_cast<uint32_t>(cob::kSdoRx + id) && !frame.extended()) handle_sdo(frame);
}

void EmulatedDrive::handle_nmt(const NmtMessage& message) {
  switch (message.command) {
    case NmtCommand::kStart:
      if (nmt_ != NmtState::kOperational) {
        nmt_ = NmtState::kOperational;
        for (PdoChannel& pdo : tpdo_) {
          pdo.sync_count = 0;
          pdo.sent_once = false;
          pdo.next_event_ns = now_ns_ + int64_t{pdo.event_timer_ms} * 1'000'000;
        }
      }
      break;
    case NmtCommand::kStop:
      nmt_ = NmtState::kStopped;
      break;
    case NmtCommand::kEnterPreOperational:
      nmt_ = NmtState::kPreOperational;
      break;
    case NmtCommand::kResetNode:
      reset_application();
      reset_communication();
      initialising_ = true;
      nmt_ = NmtState::kBootUp;
      break;
    case NmtCommand::kResetCommunication:
      reset_communication();
      initialising_ = true;
      nmt_ = NmtState::kBootUp;
      break;
  }
  if (nmt_ != NmtState::kOperational) {
    for (PdoChannel& pdo : rpdo_) pdo.pending = false;
  }
}

void EmulatedDrive::handle_sync() {
  ++stats_.syncs;
  if (nmt_ != NmtState::kOperational) return;
  // synchronous RPDOs received since the last SYNC take effect now
  for (PdoChannel& pdo : rpdo_) {
    if (pdo.pending) {
      pdo.pending = false;
      apply_rpdo(pdo, pdo.pending_values);
    }
  }
  // synchronous TPDOs are sampled now
  for (PdoChannel& pdo : tpdo_) {
    if (!pdo.valid() || pdo.transmission_type > 240) continue;
    if (pdo.transmission_type == 0) {
      send_tpdo(pdo);  // acyclic: only sent when the data changed
      continue;
    }
    if (++pdo.sync_count >= pdo.transmission_type) {
      pdo.sync_count = 0;
      send_tpdo(pdo);
    }
  }
}

void EmulatedDrive::handle_rpdo(PdoChannel& pdo, const CanFrame& frame) {
  if (drop_rpdos_ > 0) {
    if (drop_rpdos_ != kDropForever) --drop_rpdos_;
    ++stats_.rpdos_dropped;
    return;
  }
  if (pdo.mapping.empty()) return;
  std::array<uint64_t, PdoMapping::kMaxEntries> values{};
  const CanError error = decode_pdo(frame, pdo.mapping, std::span<uint64_t>(values.data(), pdo.mapping.size()));
  if (error == CanError::kInvalidDlc) {
    // CiA 301: a PDO shorter than its mapping is not processed and reported
    send_emcy(emcy::kPdoLengthError, error_register_ | error_register_for(emcy::kPdoLengthError), {});
    return;
  }
  if (error != CanError::kNone) {
    ++stats_.malformed_frames;
    return;
  }
  ++stats_.rpdos_received;
  if (pdo.transmission_type <= 240) {
    pdo.pending = true;
    pdo.pending_values = values;
  } else {
    apply_rpdo(pdo, values);
  }
}

void EmulatedDrive::apply_rpdo(const PdoChannel& pdo, const std::array<uint64_t, PdoMapping::kMaxEntries>& values) {
  for (size_t i = 0; i < pdo.mapping.size(); ++i) {
    const PdoMapEntry& entry = pdo.mapping[i];
    if (entry.dummy()) continue;
    (void)write_object(entry.index, entry.subindex, static_cast<uint32_t>(values[i]));  // validated when mapped
  }
}

void EmulatedDrive::send_tpdo(PdoChannel& pdo) {
  std::array<uint64_t, PdoMapping::kMaxEntries> values{};
  for (size_t i = 0; i < pdo.mapping.size(); ++i) {
    uint32_t value = 0;
    (void)read_object(pdo.mapping[i].index, pdo.mapping[i].subindex, value);  // validated when mapped
    values[i] = value;
  }
  const auto frame = encode_pdo(static_cast<uint16_t>(pdo.cob_id & CanFrame::kMaxStandardId), pdo.mapping,
                                std::span<const uint64_t>(values.data(), pdo.mapping.size()));
  if (!frame.ok()) return;
  if (pdo.transmission_type == 0 && pdo.sent_once && *frame == pdo.last_sent) return;
  pdo.last_sent = *frame;
  pdo.sent_once = true;
  emit_tpdo(*frame);
}

void EmulatedDrive::emit_tpdo(const CanFrame& frame) {
  if (drop_tpdos_ > 0) {
    if (drop_tpdos_ != kDropForever) --drop_tpdos_;
    ++stats_.tpdos_dropped;
    return;
  }
  if (tpdo_delay_ns_ > 0) {
    if (delayed_count_ == kDelayQueue) {
      ++stats_.tpdos_dropped;
      return;
    }
    delayed_[delayed_count_++] = {frame, now_ns_ + tpdo_delay_ns_};
    return;
  }
  send(frame);
  ++stats_.tpdos_sent;
}

void EmulatedDrive::send_emcy(uint16_t error_code, uint8_t error_register, const std::array<uint8_t, 5>& vendor) {
  // EMCY is a pre-operational / operational service
  if (initialising_ || nmt_ == NmtState::kStopped) return;
  EmcyMessage message;
  message.node = config_.node_id;
  message.error_code = error_code;
  message.error_register = error_register;
  message.vendor = vendor;
  if (const auto frame = encode_emcy(message); frame.ok()) {
    send(*frame);
    ++stats_.emcys_sent;
  }
}

// ---------------------------------------------------------------------------------------------
// SDO server

void EmulatedDrive::handle_sdo(const CanFrame& frame) {
  if (nmt_ == NmtState::kStopped) return;
  ++stats_.sdo_requests;
  const NodeId id = config_.node_id;
  const uint16_t index = frame.dlc >= 3 ? le::get_u16(&frame.data[1]) : 0;
  const uint8_t subindex = frame.dlc >= 4 ? frame.data[3] : 0;
  auto abort = [&](uint32_t code) {
    if (const auto f = encode_sdo_abort(id, index, subindex, code, true); f.ok()) {
      send(*f);
      ++stats_.sdo_aborts_sent;
    }
  };

  const auto request = decode_sdo_request(frame);
  if (!request.ok()) {
    if (request.error() == CanError::kUnsupported || request.error() == CanError::kInvalidCommand) {
      abort(sdo_abort::kInvalidCommand);
    } else {
      ++stats_.malformed_frames;  // not an SDO frame at all (dlc, RTR): no answer
    }
    return;
  }
  if (request->type == SdoType::kAbort) return;  // nothing is in progress with expedited transfers
  if (sdo_refused_ && index != hand_od::kFaultInjection) {
    abort(sdo_abort::kLocalControl);
    return;
  }

  ObjectInfo info;
  uint32_t code = 0;
  if (!find_object(index, subindex, info, code)) {
    abort(code);
    return;
  }
  const auto bytes = static_cast<uint8_t>((info.bits + 7) / 8);

  if (request->type == SdoType::kUploadRequest) {
    uint32_t value = 0;
    if ((code = read_object(index, subindex, value)) != 0) {
      abort(code);
      return;
    }
    if (const auto f = encode_sdo_upload_response(id, index, subindex, mask_to_bits(value, bytes * 8), bytes); f.ok()) {
      send(*f);
    }
    return;
  }

  // download
  if (!info.writable) {
    abort(sdo_abort::kReadOnly);
    return;
  }
  if (request->size != 0 && request->size != bytes) {
    abort(request->size > bytes ? sdo_abort::kLengthTooHigh : sdo_abort::kLengthTooLow);
    return;
  }
  if ((code = write_object(index, subindex, mask_to_bits(request->data, bytes * 8))) != 0) {
    abort(code);
    return;
  }
  if (const auto f = encode_sdo_download_response(id, index, subindex); f.ok()) send(*f);
}

// ---------------------------------------------------------------------------------------------
// object dictionary

bool EmulatedDrive::find_object(uint16_t index, uint8_t subindex, ObjectInfo& info, uint32_t& abort) const {
  const uint16_t base = index & 0xFF00;
  const unsigned n = index & 0xFF;
  if ((base == 0x1400 || base == 0x1800) && n < kPdoCount) {
    const bool transmit = base == 0x1800;
    switch (subindex) {
      case 0:
        info = {8, false, false, false};
        return true;
      case 1:
        info = {32, true, false, false};
        return true;
      case 2:
        info = {8, true, false, false};
        return true;
      case 3:
      case 5:
        if (transmit) {
          info = {16, true, false, false};
          return true;
        }
        break;
      default:
        break;
    }
    abort = sdo_abort::kNoSubindex;
    return false;
  }
  if ((base == 0x1600 || base == 0x1A00) && n < kPdoCount) {
    if (subindex == 0) {
      info = {8, true, false, false};
      return true;
    }
    if (subindex <= PdoMapping::kMaxEntries) {
      info = {32, true, false, false};
      return true;
    }
    abort = sdo_abort::kNoSubindex;
    return false;
  }
  bool index_exists = false;
  for (const ObjectEntry& e : kObjects) {
    if (e.index != index) continue;
    index_exists = true;
    if (e.subindex == subindex) {
      info = {e.bits, e.writable, e.rx_mappable, e.tx_mappable};
      return true;
    }
  }
  abort = index_exists ? sdo_abort::kNoSubindex : sdo_abort::kNoObject;
  return false;
}

uint32_t EmulatedDrive::read_object(uint16_t index, uint8_t subindex, uint32_t& value) const {
  const uint16_t base = index & 0xFF00;
  const unsigned n = index & 0xFF;
  if ((base == 0x1400 || base == 0x1800) && n < kPdoCount) {
    const PdoChannel& pdo = base == 0x1400 ? rpdo_[n] : tpdo_[n];
    switch (subindex) {
      case 0:
        value = base == 0x1400 ? 2 : 5;
        return 0;
      case 1:
        value = pdo.cob_id;
        return 0;
      case 2:
        value = pdo.transmission_type;
        return 0;
      case 3:
        value = pdo.inhibit_100us;
        return 0;
      case 5:
        value = pdo.event_timer_ms;
        return 0;
      default:
        return sdo_abort::kNoSubindex;
    }
  }
  if ((base == 0x1600 || base == 0x1A00) && n < kPdoCount) {
    const PdoChannel& pdo = base == 0x1600 ? rpdo_[n] : tpdo_[n];
    if (subindex == 0) {
      value = pdo.map_count;
      return 0;
    }
    if (subindex > PdoMapping::kMaxEntries) return sdo_abort::kNoSubindex;
    value = pdo.map_raw[subindex - 1];
    return 0;
  }
  switch (index) {
    case 0x1000:
      value = kDeviceType;
      return 0;
    case 0x1001:
      value = error_register_;
      return 0;
    case 0x1017:
      value = heartbeat_ms_;
      return 0;
    case 0x1018:
      switch (subindex) {
        case 0:
          value = 4;
          return 0;
        case 1:
          value = config_.vendor_id;
          return 0;
        case 2:
          value = config_.product_code;
          return 0;
        case 3:
          value = config_.revision;
          return 0;
        case 4:
          value = config_.serial;
          return 0;
        default:
          return sdo_abort::kNoSubindex;
      }
    case od::kErrorCode:
      value = error_code_;
      return 0;
    case od::kControlword:
      value = controlword_;
      return 0;
    case od::kStatusword:
      value = statusword();
      return 0;
    case od::kModesOfOperation:
    case od::kModesOfOperationDisplay:
      value = static_cast<uint8_t>(mode_);
      return 0;
    case od::kPositionActualValue:
      value = static_cast<uint32_t>(position_ticks());
      return 0;
    case od::kFollowingErrorWindow:
      value = following_error_window_ticks_;
      return 0;
    case od::kFollowingErrorTimeout:
      value = following_error_timeout_ms_;
      return 0;
    case od::kVelocityActualValue:
      value = static_cast<uint32_t>(saturate_int32(velocity_filtered_radps_ * ticks_per_rad_));
      return 0;
    case od::kMaxCurrent:
      value = max_current_permille_;
      return 0;
    case od::kMotorRatedCurrent:
      value = static_cast<uint32_t>(std::lround(config_.rated_current_a * 1e3));
      return 0;
    case od::kTorqueActualValue:  // a DC motor: torque per mille of rated = current per mille of rated
    case od::kCurrentActualValue:
      value = static_cast<uint16_t>(saturate_int16(current_a_ / config_.rated_current_a * 1e3));
      return 0;
    case od::kTargetPosition:
      value = static_cast<uint32_t>(target_ticks_);
      return 0;
    case hand_od::kGains:
      return read_gain(subindex, value);
    case hand_od::kFaultInjection:
      return read_injection(subindex, value);
    case od::kSoftwarePositionLimit:
      switch (subindex) {
        case 0:
          value = 2;
          return 0;
        case 1:
          value = static_cast<uint32_t>(limit_min_ticks_);
          return 0;
        case 2:
          value = static_cast<uint32_t>(limit_max_ticks_);
          return 0;
        default:
          return sdo_abort::kNoSubindex;
      }
    default:
      break;
  }
  return sdo_abort::kNoObject;
}

uint32_t EmulatedDrive::write_object(uint16_t index, uint8_t subindex, uint32_t value) {
  const uint16_t base = index & 0xFF00;
  const unsigned n = index & 0xFF;
  if ((base == 0x1400 || base == 0x1800) && n < kPdoCount) {
    return write_pdo_communication(base == 0x1400 ? rpdo_[n] : tpdo_[n], base == 0x1800, subindex, value);
  }
  if ((base == 0x1600 || base == 0x1A00) && n < kPdoCount) {
    return write_pdo_mapping(base == 0x1600 ? rpdo_[n] : tpdo_[n], base == 0x1A00, subindex, value);
  }
  switch (index) {
    case 0x1017:
      heartbeat_ms_ = static_cast<uint16_t>(value);
      next_heartbeat_ns_ = now_ns_ + int64_t{heartbeat_ms_} * 1'000'000;
      return 0;
    case od::kControlword:
      set_controlword(static_cast<uint16_t>(value));
      return 0;
    case od::kModesOfOperation: {
      const auto mode = static_cast<int8_t>(static_cast<uint8_t>(value));
      if (mode != cia402::kModeNone && mode != cia402::kModeCyclicSynchronousPosition) {
        return sdo_abort::kInvalidValue;
      }
      mode_ = mode;
      return 0;
    }
    case od::kFollowingErrorWindow:
      following_error_window_ticks_ = value;
      return 0;
    case od::kFollowingErrorTimeout:
      following_error_timeout_ms_ = static_cast<uint16_t>(value);
      return 0;
    case od::kMaxCurrent: {
      const double peak_permille = config_.peak_current_a / config_.rated_current_a * 1e3;
      if (static_cast<double>(static_cast<uint16_t>(value)) > peak_permille + 0.5) return sdo_abort::kValueTooHigh;
      max_current_permille_ = static_cast<uint16_t>(value);
      return 0;
    }
    case od::kTargetPosition:
      target_ticks_ = static_cast<int32_t>(value);
      return 0;
    case hand_od::kGains:
      return write_gain(subindex, value);
    case hand_od::kFaultInjection:
      return write_injection(subindex, value);
    case od::kSoftwarePositionLimit:
      if (subindex == 1) limit_min_ticks_ = static_cast<int32_t>(value);
      if (subindex == 2) limit_max_ticks_ = static_cast<int32_t>(value);
      return subindex == 1 || subindex == 2 ? 0 : sdo_abort::kReadOnly;
    default:
      break;
  }
  return sdo_abort::kReadOnly;
}

uint32_t EmulatedDrive::read_gain(uint8_t subindex, uint32_t& value) const {
  if (subindex == 0) {
    value = hand_od::gain::kCount;
    return 0;
  }
  const double* slot = gain_slot(config_.control, subindex);
  if (slot == nullptr) return sdo_abort::kNoSubindex;
  value = hand_od::real32_bits(*slot);
  return 0;
}

uint32_t EmulatedDrive::write_gain(uint8_t subindex, uint32_t value) {
  double* slot = gain_slot(config_.control, subindex);
  if (slot == nullptr) return sdo_abort::kReadOnly;
  const double gain = hand_od::real32_value(value);
  if (!std::isfinite(gain)) return sdo_abort::kInvalidValue;
  if (gain < 0) return sdo_abort::kValueTooLow;
  // the reference step limit must stay positive, or the reference could never move
  if (subindex == hand_od::gain::kMaxReferenceVelocity && gain <= 0) return sdo_abort::kValueTooLow;
  *slot = gain;
  return 0;
}

uint32_t EmulatedDrive::read_injection(uint8_t subindex, uint32_t& value) const {
  switch (subindex) {
    case 0:
      value = hand_od::inject::kCount;
      return 0;
    case hand_od::inject::kSuppressHeartbeat:
      value = heartbeat_suppressed_ ? 1 : 0;
      return 0;
    case hand_od::inject::kRaiseFault:
      value = error_code_;
      return 0;
    case hand_od::inject::kStall:
      value = stalled_ ? 1 : 0;
      return 0;
    case hand_od::inject::kDropTpdos:
      value = drop_tpdos_;
      return 0;
    case hand_od::inject::kRefuseSdo:
      value = sdo_refused_ ? 1 : 0;
      return 0;
    case hand_od::inject::kDropRpdos:
      value = drop_rpdos_;
      return 0;
    default:
      return sdo_abort::kNoSubindex;
  }
}

uint32_t EmulatedDrive::write_injection(uint8_t subindex, uint32_t value) {
  switch (subindex) {
    case hand_od::inject::kSuppressHeartbeat:
      set_heartbeat_suppressed(value != 0);
      return 0;
    case hand_od::inject::kRaiseFault:
      if (value == 0 || value > 0xFFFF) return sdo_abort::kInvalidValue;
      raise_fault(static_cast<uint16_t>(value));
      return 0;
    case hand_od::inject::kStall:
      set_stalled(value != 0);
      return 0;
    case hand_od::inject::kDropTpdos:
      drop_tpdos(value);
      return 0;
    case hand_od::inject::kRefuseSdo:
      set_sdo_refused(value != 0);
      return 0;
    case hand_od::inject::kDropRpdos:
      drop_rpdos(value);
      return 0;
    default:
      return sdo_abort::kReadOnly;
  }
}

uint32_t EmulatedDrive::write_pdo_communication(PdoChannel& pdo, bool transmit, uint8_t subindex, uint32_t value) {
  switch (subindex) {
    case 1: {
      // 11-bit ids only; a valid PDO's id cannot change (disable it first)
      if ((value & kPdoExtendedId) || (value & 0x1FFFF800u)) return sdo_abort::kInvalidValue;
      if (!(value & kPdoInvalid) && restricted_cob_id(value & CanFrame::kMaxStandardId))
        return sdo_abort::kInvalidValue;
      const bool stays_valid = pdo.valid() && !(value & kPdoInvalid);
      if (stays_valid && (value & CanFrame::kMaxStandardId) != (pdo.cob_id & CanFrame::kMaxStandardId)) {
        return sdo_abort::kInvalidValue;
      }
      pdo.cob_id = value & (kPdoInvalid | CanFrame::kMaxStandardId);
      pdo.pending = false;
      pdo.sync_count = 0;
      pdo.sent_once = false;
      return 0;
    }
    case 2:
      if (!valid_transmission_type(value)) return sdo_abort::kInvalidValue;
      pdo.transmission_type = static_cast<uint8_t>(value);
      pdo.sync_count = 0;
      return 0;
    case 3:
      if (!transmit) return sdo_abort::kNoSubindex;
      pdo.inhibit_100us = static_cast<uint16_t>(value);  // kept, not enforced
      return 0;
    case 5:
      if (!transmit) return sdo_abort::kNoSubindex;
      pdo.event_timer_ms = static_cast<uint16_t>(value);
      pdo.next_event_ns = now_ns_ + int64_t{pdo.event_timer_ms} * 1'000'000;
      return 0;
    default:
      break;
  }
  return sdo_abort::kReadOnly;
}

uint32_t EmulatedDrive::write_pdo_mapping(PdoChannel& pdo, bool transmit, uint8_t subindex, uint32_t value) {
  // CiA 301: a mapping changes only while its PDO is not valid, entries only while sub 0 is 0
  if (pdo.valid()) return sdo_abort::kUnsupportedAccess;
  if (subindex != 0) {
    if (pdo.map_count != 0) return sdo_abort::kUnsupportedAccess;
    pdo.map_raw[subindex - 1] = value;
    return 0;
  }
  if (value > PdoMapping::kMaxEntries) return sdo_abort::kMappingTooLong;
  PdoMapping mapping;
  for (uint32_t i = 0; i < value; ++i) {
    const PdoMapEntry entry = PdoMapEntry::from_u32(pdo.map_raw[i]);
    if (entry.dummy()) {
      if (transmit || entry.subindex != 0 || entry.bits != dummy_bits(entry.index)) return sdo_abort::kNotMappable;
    } else {
      ObjectInfo info;
      uint32_t abort = 0;
      if (!find_object(entry.index, entry.subindex, info, abort)) return sdo_abort::kNotMappable;
      if (transmit ? !info.tx_mappable : !info.rx_mappable) return sdo_abort::kNotMappable;
      if (entry.bits != info.bits) return sdo_abort::kNotMappable;
    }
    if (mapping.add(entry) != CanError::kNone) return sdo_abort::kMappingTooLong;
  }
  pdo.mapping = mapping;
  pdo.map_count = static_cast<uint8_t>(value);
  return 0;
}

// ---------------------------------------------------------------------------------------------
// CiA 402

uint16_t EmulatedDrive::statusword() const {
  uint16_t s = cia402::statusword_for(state_) | cia402::sw::kRemote;
  if (state_ != State::kNotReadyToSwitchOn) s |= cia402::sw::kVoltageEnabled;
  if (internal_limit_) s |= cia402::sw::kInternalLimitActive;
  if (following_error_) s |= cia402::sw::kFollowingError;
  if (state_ == State::kOperationEnabled && mode_ == cia402::kModeCyclicSynchronousPosition) {
    s |= cia402::sw::kDriveFollowsCommand;
  }
  return s;
}

void EmulatedDrive::set_controlword(uint16_t controlword) {
  const uint16_t previous = controlword_;
  controlword_ = controlword;
  evaluate_controlword(previous);
}

void EmulatedDrive::evaluate_controlword(uint16_t previous) {
  if (initialising_) return;
  const cia402::Command command = cia402::command_from_controlword(controlword_, previous);
  const State next = cia402::next_state(state_, command);
  if (next == state_) return;
  if (state_ == State::kFault) {
    // transition 15: the error is acknowledged; CiA 301 announces it with error code 0
    error_code_ = 0;
    error_register_ = 0;
    following_error_ = false;
    following_error_ns_ = 0;
    send_emcy(emcy::kErrorReset, 0, {});
  }
  enter_state(next);
}

bool EmulatedDrive::power_on() const { return state_ == State::kOperationEnabled || state_ == State::kQuickStopActive; }

void EmulatedDrive::enter_state(State next) {
  if (next == state_) return;
  const bool was_powered = power_on();
  state_ = next;
  const double q_meas = position_ticks() / ticks_per_rad_;
  if (power_on() && !was_powered) {
    // bumpless start from where the link is
    ref_rad_ = q_meas;
    ref_velocity_radps_ = 0;
    position_integral_a_ = 0;
    current_integral_v_ = 0;
    following_error_ns_ = 0;
  }
  if (next == State::kQuickStopActive) {
    // hold where the quick stop found the link
    ref_rad_ = q_meas;
    ref_velocity_radps_ = 0;
  }
  if (next == State::kFaultReactionActive) {
    fault_reaction_remaining_ns_ = std::llround(config_.fault_reaction_time_s * 1e9);
  }
  if (!power_on()) {
    current_ref_a_ = 0;
    position_integral_a_ = 0;
    current_integral_v_ = 0;
    internal_limit_ = false;
  }
}

void EmulatedDrive::enter_fault(uint16_t error_code, const std::array<uint8_t, 5>& vendor) {
  error_code_ = error_code;
  error_register_ = error_register_for(error_code);
  send_emcy(error_code, error_register_, vendor);
  if (state_ != State::kFault && state_ != State::kFaultReactionActive) enter_state(State::kFaultReactionActive);
}

void EmulatedDrive::raise_fault(uint16_t error_code, const std::array<uint8_t, 5>& vendor) {
  enter_fault(error_code, vendor);
}

void EmulatedDrive::set_tpdo_delay(double seconds) {
  tpdo_delay_ns_ = std::isfinite(seconds) && seconds > 0 ? std::llround(seconds * 1e9) : 0;
}

double EmulatedDrive::current_limit_a() const {
  return std::min(max_current_permille_ * 1e-3 * config_.rated_current_a, config_.peak_current_a);
}

int32_t EmulatedDrive::position_ticks() const { return saturate_int32(q_rad_ * ticks_per_rad_); }

// ---------------------------------------------------------------------------------------------
// physics and control

void EmulatedDrive::position_loop() {
  const EmulatedControllerParams& c = config_.control;
  const double period_s = c.substep_s * c.position_loop_divider;
  // the drive sees the link through its encoder
  const double q_meas = position_ticks() / ticks_per_rad_;
  const double v_raw = (q_meas - q_meas_prev_rad_) / period_s;
  q_meas_prev_rad_ = q_meas;
  velocity_filtered_radps_ += velocity_filter_alpha_ * (v_raw - velocity_filtered_radps_);

  if (!power_on()) {
    ref_rad_ = q_meas;
    ref_velocity_radps_ = 0;
    current_ref_a_ = 0;
    return;
  }

  // reference: the target within the software limits, approached at most one step per period
  bool limited = false;
  if (state_ == State::kOperationEnabled && mode_ == cia402::kModeCyclicSynchronousPosition) {
    int32_t target = target_ticks_;
    if (limit_min_ticks_ < limit_max_ticks_) {
      if (target < limit_min_ticks_) {
        target = limit_min_ticks_;
        limited = true;
      } else if (target > limit_max_ticks_) {
        target = limit_max_ticks_;
        limited = true;
      }
    }
    const double max_step = c.max_reference_velocity_radps * period_s;
    const double step = std::clamp(target / ticks_per_rad_ - ref_rad_, -max_step, max_step);
    ref_rad_ += step;
    ref_velocity_radps_ = step / period_s;
  } else {
    ref_velocity_radps_ = 0;  // quick stop or no mode: hold
  }

  // PID with derivative on the error (the reference is rate-limited, so there is no kick)
  const double error = ref_rad_ - q_meas;
  const double derror = ref_velocity_radps_ - velocity_filtered_radps_;
  const double limit_a = current_limit_a();
  const double unsaturated =
      c.position_kp_a_per_rad * error + position_integral_a_ + c.position_kd_a_s_per_rad * derror;
  const double command = std::clamp(unsaturated, -limit_a, limit_a);
  if (command != unsaturated) limited = true;
  // anti-windup: integrate unless saturated and the error would push further into saturation
  if (command == unsaturated || (error > 0) != (unsaturated > 0)) {
    const double integral_limit = std::min(c.position_integral_limit_a, limit_a);
    position_integral_a_ = std::clamp(position_integral_a_ + c.position_ki_a_per_rad_s * error * period_s,
                                      -integral_limit, integral_limit);
  }
  current_ref_a_ = command;
  internal_limit_ = limited;

  // following error: the link stays too far from the demand for too long
  const int64_t period_ns = substep_ns_ * c.position_loop_divider;
  if (following_error_window_ticks_ != kFollowingErrorOff &&
      std::fabs(error) * ticks_per_rad_ > static_cast<double>(following_error_window_ticks_)) {
    following_error_ns_ += period_ns;
    if (following_error_ns_ >= int64_t{following_error_timeout_ms_} * 1'000'000 && !following_error_) {
      following_error_ = true;
      enter_fault(emcy::kFollowingError, {});
    }
  } else {
    following_error_ns_ = 0;
  }
}

void EmulatedDrive::substep() {
  const EmulatedControllerParams& c = config_.control;
  const EmulatedMotorParams& m = config_.motor;
  const double dt = c.substep_s;

  if (substep_count_ % c.position_loop_divider == 0) position_loop();
  ++substep_count_;

  // current PI -> PWM (average model: the bridge applies duty * supply)
  const double omega_motor = dq_radps_ * m.gear_ratio;
  if (power_on()) {
    const double error = current_ref_a_ - current_a_;
    const double unsaturated = c.current_kp_v_per_a * error + current_integral_v_;
    const double volts = std::clamp(unsaturated, -m.supply_v, m.supply_v);
    if (volts == unsaturated || (error > 0) != (unsaturated > 0)) {
      current_integral_v_ =
          std::clamp(current_integral_v_ + c.current_ki_v_per_a_s * error * dt, -m.supply_v, m.supply_v);
    }
    const double duty = volts / m.supply_v;
    voltage_v_ = duty * m.supply_v;
    // winding: L di/dt = V - R i - k omega, exact for V and omega constant over the substep
    const double steady = (voltage_v_ - m.torque_constant_nm_per_a * omega_motor) / m.resistance_ohm;
    current_a_ = steady + (current_a_ - steady) * current_decay_;
  } else {
    // bridge off: the current dies out through the free-wheeling diodes at once
    voltage_v_ = 0;
    current_a_ = 0;
  }

  // link: J ddq = N eta k i - b dq + hard stops (penalty spring-damper that only pushes)
  if (stalled_) {
    dq_radps_ = 0;
  } else {
    double torque =
        m.gear_ratio * m.gear_efficiency * m.torque_constant_nm_per_a * current_a_ - m.viscous_nms_per_rad * dq_radps_;
    if (q_rad_ > m.stop_max_rad) {
      torque += std::min(
          0.0, -m.stop_stiffness_nm_per_rad * (q_rad_ - m.stop_max_rad) - m.stop_damping_nms_per_rad * dq_radps_);
    } else if (q_rad_ < m.stop_min_rad) {
      torque += std::max(
          0.0, -m.stop_stiffness_nm_per_rad * (q_rad_ - m.stop_min_rad) - m.stop_damping_nms_per_rad * dq_radps_);
    }
    const double inertia = m.link_inertia_kgm2 + m.rotor_inertia_kgm2 * m.gear_ratio * m.gear_ratio;
    dq_radps_ += torque / inertia * dt;
    q_rad_ += dq_radps_ * dt;
  }

  // fault reaction (power already off) ends in fault
  if (state_ == State::kFaultReactionActive) {
    fault_reaction_remaining_ns_ -= substep_ns_;
    if (fault_reaction_remaining_ns_ <= 0) enter_state(State::kFault);
  }
}

}  // namespace teleop::hand
