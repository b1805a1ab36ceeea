#include "pdo_engine.h"

#include <span>

#include "object_dictionary.h"

namespace teleop::drive {

namespace sdo_abort = can::sdo_abort;
using can::CanError;
using can::CanFrame;
using can::PdoMapEntry;
using can::PdoMapping;

namespace {

constexpr uint32_t kPdoInvalid = 0x80000000u;
constexpr uint32_t kPdoExtendedId = 0x20000000u;

// length in bits of the data-type "objects" 0x0001..0x0007 used as dummy mapping entries
constexpr uint8_t kDummyBits[] = {0, 1, 8, 16, 32, 8, 16, 32};
uint8_t dummy_bits(uint16_t index) { return index < 8 ? kDummyBits[index] : 0; }

bool valid_transmission_type(uint32_t type) { return type <= 240 || type == 254 || type == 255; }

// COB-IDs CiA 301 reserves for NMT, SDO, NMT error control and LSS, plus SYNC (0x080), which
// this drive would otherwise take for a PDO
bool restricted_cob_id(uint32_t id) {
  return id <= 0x080 || (id >= 0x101 && id <= 0x180) || (id >= 0x581 && id <= 0x5FF) || (id >= 0x601 && id <= 0x67F) ||
         (id >= 0x6E0 && id <= 0x6FF) || id >= 0x701;
}

int64_t ms_to_ns(uint16_t ms) { return int64_t{ms} * 1'000'000; }

}  // namespace

PdoEngine::PdoEngine(DriveLink& link, FaultInjection& faults, NmtSlave& nmt, const Cia402Device& device)
    : link_(link), faults_(faults), nmt_(nmt), device_(device) {}

void PdoEngine::reset(can::NodeId node) {
  rpdo_ = {};
  tpdo_ = {};
  rpdo_[0].cob_id = can::rpdo_cob_id(1, node);
  rpdo_[0].map_raw = {0x60400010, 0x607A0020};
  rpdo_[0].map_count = 2;
  rpdo_[1].cob_id = kPdoInvalid | can::rpdo_cob_id(2, node);
  tpdo_[0].cob_id = can::tpdo_cob_id(1, node);
  tpdo_[0].map_raw = {0x60640020, 0x60780010, 0x60410010};
  tpdo_[0].map_count = 3;
  tpdo_[1].cob_id = kPdoInvalid | can::tpdo_cob_id(2, node);
  tpdo_[1].map_raw = {0x606C0020, 0x603F0010};
  tpdo_[1].map_count = 2;
  for (Channel* pdo : {&rpdo_[0], &rpdo_[1], &tpdo_[0], &tpdo_[1]}) {
    pdo->transmission_type = 1;
    for (uint8_t i = 0; i < pdo->map_count; ++i) {
      (void)pdo->mapping.add(PdoMapEntry::from_u32(pdo->map_raw[i]));  // known-good defaults
    }
  }
}

void PdoEngine::start(int64_t now_ns) {
  for (Channel& pdo : tpdo_) {
    pdo.sync_count = 0;
    pdo.sent_once = false;
    pdo.next_event_ns = now_ns + ms_to_ns(pdo.event_timer_ms);
  }
}

void PdoEngine::forget_pending() {
  for (Channel& pdo : rpdo_) pdo.pending = false;
}

bool PdoEngine::receive(const CanFrame& frame, ObjectDictionary& objects) {
  // PDO COB-IDs are configurable: they are looked at before the fixed services
  if (!nmt_.operational() || frame.extended() || frame.rtr()) return false;
  for (Channel& pdo : rpdo_) {
    if (pdo.valid() && (pdo.cob_id & CanFrame::kMaxStandardId) == frame.id) {
      handle_rpdo(pdo, frame, objects);
      return true;
    }
  }
  return false;
}

void PdoEngine::handle_rpdo(Channel& pdo, const CanFrame& frame, ObjectDictionary& objects) {
  if (faults_.drop_rpdo()) return;
  if (pdo.mapping.empty()) return;
  Values values{};
  const CanError error = can::decode_pdo(frame, pdo.mapping, std::span<uint64_t>(values.data(), pdo.mapping.size()));
  if (error == CanError::kInvalidDlc) {
    // CiA 301: a PDO shorter than its mapping is not processed and reported
    nmt_.send_emcy(can::emcy::kPdoLengthError,
                   device_.error_register() | can::error_register_for(can::emcy::kPdoLengthError), {});
    return;
  }
  if (error != CanError::kNone) {
    ++link_.stats().malformed_frames;
    return;
  }
  ++link_.stats().rpdos_received;
  if (pdo.transmission_type <= 240) {
    pdo.pending = true;
    pdo.pending_values = values;
  } else {
    apply(pdo, values, objects);
  }
}

void PdoEngine::apply(const Channel& pdo, const Values& values, ObjectDictionary& objects) {
  for (size_t i = 0; i < pdo.mapping.size(); ++i) {
    const PdoMapEntry& entry = pdo.mapping[i];
    if (entry.dummy()) continue;
    (void)objects.write(entry.index, entry.subindex, static_cast<uint32_t>(values[i]));  // validated when mapped
  }
}

void PdoEngine::sync(ObjectDictionary& objects, int64_t now_ns) {
  ++link_.stats().syncs;
  if (!nmt_.operational()) return;
  // synchronous RPDOs received since the last SYNC take effect now
  for (Channel& pdo : rpdo_) {
    if (pdo.pending) {
      pdo.pending = false;
      apply(pdo, pdo.pending_values, objects);
    }
  }
  // synchronous TPDOs are sampled now
  for (Channel& pdo : tpdo_) {
    if (!pdo.valid() || pdo.transmission_type > 240) continue;
    if (pdo.transmission_type == 0) {
      send_tpdo(pdo, objects, now_ns);  // acyclic: only sent when the data changed
      continue;
    }
    if (++pdo.sync_count >= pdo.transmission_type) {
      pdo.sync_count = 0;
      send_tpdo(pdo, objects, now_ns);
    }
  }
}

void PdoEngine::service_event_timers(const ObjectDictionary& objects, int64_t now_ns) {
  if (!nmt_.operational()) return;
  for (Channel& pdo : tpdo_) {
    if (!pdo.valid() || pdo.transmission_type < 254 || pdo.event_timer_ms == 0) continue;
    if (now_ns < pdo.next_event_ns) continue;
    send_tpdo(pdo, objects, now_ns);
    const int64_t period_ns = ms_to_ns(pdo.event_timer_ms);
    pdo.next_event_ns += period_ns;
    if (pdo.next_event_ns <= now_ns) pdo.next_event_ns = now_ns + period_ns;
  }
}

void PdoEngine::send_tpdo(Channel& pdo, const ObjectDictionary& objects, int64_t now_ns) {
  Values values{};
  for (size_t i = 0; i < pdo.mapping.size(); ++i) {
    uint32_t value = 0;
    (void)objects.read(pdo.mapping[i].index, pdo.mapping[i].subindex, value);  // validated when mapped
    values[i] = value;
  }
  const auto frame = can::encode_pdo(static_cast<uint16_t>(pdo.cob_id & CanFrame::kMaxStandardId), pdo.mapping,
                                     std::span<const uint64_t>(values.data(), pdo.mapping.size()));
  if (!frame.ok()) return;
  if (pdo.transmission_type == 0 && pdo.sent_once && *frame == pdo.last_sent) return;
  pdo.last_sent = *frame;
  pdo.sent_once = true;
  faults_.emit_tpdo(*frame, now_ns);
}

uint32_t PdoEngine::communication(bool transmit, size_t n, uint8_t subindex) const {
  const Channel& pdo = channel(transmit, n);
  switch (subindex) {
    case 0:
      return transmit ? 5 : 2;  // highest subindex
    case 1:
      return pdo.cob_id;
    case 2:
      return pdo.transmission_type;
    case 3:
      return pdo.inhibit_100us;
    default:
      return pdo.event_timer_ms;  // 5: the dictionary has no other subindex
  }
}

uint32_t PdoEngine::write_communication(bool transmit, size_t n, uint8_t subindex, uint32_t value, int64_t now_ns) {
  Channel& pdo = channel(transmit, n);
  switch (subindex) {
    case 1: {
      // 11-bit ids only; a valid PDO's id cannot change (disable it first)
      if ((value & kPdoExtendedId) || (value & 0x1FFFF800u)) return sdo_abort::kInvalidValue;
      if (!(value & kPdoInvalid) && restricted_cob_id(value & CanFrame::kMaxStandardId)) {
        return sdo_abort::kInvalidValue;
      }
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
      pdo.inhibit_100us = static_cast<uint16_t>(value);  // kept, not enforced
      return 0;
    default:  // 5: the dictionary has no other writable subindex
      pdo.event_timer_ms = static_cast<uint16_t>(value);
      pdo.next_event_ns = now_ns + ms_to_ns(pdo.event_timer_ms);
      return 0;
  }
}

uint32_t PdoEngine::mapping(bool transmit, size_t n, uint8_t subindex) const {
  const Channel& pdo = channel(transmit, n);
  return subindex == 0 ? pdo.map_count : pdo.map_raw[subindex - 1];
}

uint32_t PdoEngine::write_mapping(bool transmit, size_t n, uint8_t subindex, uint32_t value) {
  Channel& pdo = channel(transmit, n);
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
      if (ObjectDictionary::find(entry.index, entry.subindex, info) != 0) return sdo_abort::kNotMappable;
      if (transmit ? !info.tx_mappable : !info.rx_mappable) return sdo_abort::kNotMappable;
      if (entry.bits != info.bits) return sdo_abort::kNotMappable;
    }
    if (mapping.add(entry) != CanError::kNone) return sdo_abort::kMappingTooLong;
  }
  pdo.mapping = mapping;
  pdo.map_count = static_cast<uint8_t>(value);
  return 0;
}

}  // namespace teleop::drive
