#include "object_dictionary.h"

#include <array>
#include <cmath>

#include "teleop/can/cia301.h"
#include "teleop/can/cia402.h"
#include "teleop/hand/hand_drive_objects.h"

namespace teleop::hand::drive {

namespace od = can::cia402::od;
namespace sdo_abort = can::sdo_abort;

namespace {

// How an object is read (its value) and written (0 or an SDO abort code); a null writer makes
// the object read-only. Index and subindex tell the PDO parameters' channel and field apart.
using Reader = uint32_t (*)(const ObjectOwners&, uint16_t index, uint8_t subindex);
using Writer = uint32_t (*)(const ObjectOwners&, uint16_t index, uint8_t subindex, uint32_t value);

enum Pdo : uint8_t { kNoPdo, kRpdo, kTpdo };  // which PDOs may map the object

struct ObjectEntry {
  uint16_t index = 0;
  uint8_t subindex = 0;
  uint8_t bits = 0;
  Pdo pdo = kNoPdo;
  Reader read = nullptr;
  Writer write = nullptr;
};

// the controller parameter behind each subindex 1.. of the gains object
constexpr double EmulatedControllerParams::* kGainSlots[hand_od::gain::kCount] = {
    &EmulatedControllerParams::position_kp_a_per_rad,     &EmulatedControllerParams::position_ki_a_per_rad_s,
    &EmulatedControllerParams::position_kd_a_s_per_rad,   &EmulatedControllerParams::position_integral_limit_a,
    &EmulatedControllerParams::max_reference_velocity_radps, &EmulatedControllerParams::current_kp_v_per_a,
    &EmulatedControllerParams::current_ki_v_per_a_s};

uint32_t read_gain(const ObjectOwners& o, uint16_t, uint8_t subindex) {
  return hand_od::real32_bits(o.config.control.*kGainSlots[subindex - 1]);
}

uint32_t write_gain(const ObjectOwners& o, uint16_t, uint8_t subindex, uint32_t value) {
  const double gain = hand_od::real32_value(value);
  if (!std::isfinite(gain)) return sdo_abort::kInvalidValue;
  if (gain < 0) return sdo_abort::kValueTooLow;
  // the reference step limit must stay positive, or the reference could never move
  if (subindex == hand_od::gain::kMaxReferenceVelocity && gain <= 0) return sdo_abort::kValueTooLow;
  o.config.control.*kGainSlots[subindex - 1] = gain;
  return 0;
}

// a per mille of the rated current, as 0x6077 / 0x6078 carry it
uint32_t current_permille(const ObjectOwners& o) {
  return static_cast<uint16_t>(saturate_int16(o.motor.current_a() / o.config.rated_current_a * 1e3));
}

// the fixed objects (subindex 0 unless noted); the PDO parameters are added below
constexpr ObjectEntry kFixedObjects[] = {
    {0x1000, 0, 32, kNoPdo, [](const ObjectOwners&, uint16_t, uint8_t) -> uint32_t { return EmulatedDrive::kDeviceType; }},
    {0x1001, 0, 8, kTpdo, [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return o.device.error_register(); }},
    // producer heartbeat time [ms]; a write restarts the heartbeat timer
    {0x1017, 0, 16, kNoPdo, [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return o.nmt.heartbeat_ms(); },
     [](const ObjectOwners& o, uint16_t, uint8_t, uint32_t v) -> uint32_t {
       o.nmt.set_heartbeat_ms(static_cast<uint16_t>(v), o.now_ns);
       return 0;
     }},
    // identity: highest subindex, vendor id, product code, revision, serial number
    {0x1018, 0, 8, kNoPdo, [](const ObjectOwners&, uint16_t, uint8_t) -> uint32_t { return 4; }},
    {0x1018, 1, 32, kNoPdo, [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return o.config.vendor_id; }},
    {0x1018, 2, 32, kNoPdo, [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return o.config.product_code; }},
    {0x1018, 3, 32, kNoPdo, [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return o.config.revision; }},
    {0x1018, 4, 32, kNoPdo, [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return o.config.serial; }},
    // CiA 402
    {od::kErrorCode, 0, 16, kTpdo, [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return o.device.error_code(); }},
    {od::kControlword, 0, 16, kRpdo,
     [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return o.device.controlword(); },
     [](const ObjectOwners& o, uint16_t, uint8_t, uint32_t v) -> uint32_t {
       o.device.set_controlword(static_cast<uint16_t>(v));
       return 0;
     }},
    {od::kStatusword, 0, 16, kTpdo, [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return o.device.statusword(); }},
    {od::kModesOfOperation, 0, 8, kRpdo,
     [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return static_cast<uint8_t>(o.device.mode()); },
     [](const ObjectOwners& o, uint16_t, uint8_t, uint32_t v) -> uint32_t {
       return o.device.set_mode(static_cast<int8_t>(static_cast<uint8_t>(v))) ? 0 : sdo_abort::kInvalidValue;
     }},
    {od::kModesOfOperationDisplay, 0, 8, kTpdo,
     [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return static_cast<uint8_t>(o.device.mode()); }},
    {od::kPositionActualValue, 0, 32, kTpdo,
     [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return static_cast<uint32_t>(o.motor.encoder_ticks()); }},
    {od::kFollowingErrorWindow, 0, 32, kNoPdo,
     [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return o.device.following_error_window_ticks(); },
     [](const ObjectOwners& o, uint16_t, uint8_t, uint32_t v) -> uint32_t {
       o.device.set_following_error_window_ticks(v);
       return 0;
     }},
    {od::kFollowingErrorTimeout, 0, 16, kNoPdo,
     [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return o.device.following_error_timeout_ms(); },
     [](const ObjectOwners& o, uint16_t, uint8_t, uint32_t v) -> uint32_t {
       o.device.set_following_error_timeout_ms(static_cast<uint16_t>(v));
       return 0;
     }},
    {od::kVelocityActualValue, 0, 32, kTpdo,
     [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t {
       return static_cast<uint32_t>(saturate_int32(o.servo.velocity_estimate_radps() * o.motor.ticks_per_rad()));
     }},
    {od::kMaxCurrent, 0, 16, kRpdo,
     [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return o.device.max_current_permille(); },
     [](const ObjectOwners& o, uint16_t, uint8_t, uint32_t v) -> uint32_t {
       return o.device.set_max_current_permille(static_cast<uint16_t>(v)) ? 0 : sdo_abort::kValueTooHigh;
     }},
    {od::kMotorRatedCurrent, 0, 32, kNoPdo,
     [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t {
       return static_cast<uint32_t>(std::lround(o.config.rated_current_a * 1e3));
     }},
    // a DC motor: torque per mille of rated = current per mille of rated
    {od::kTorqueActualValue, 0, 16, kTpdo, [](const ObjectOwners& o, uint16_t, uint8_t) { return current_permille(o); }},
    {od::kCurrentActualValue, 0, 16, kTpdo, [](const ObjectOwners& o, uint16_t, uint8_t) { return current_permille(o); }},
    {od::kTargetPosition, 0, 32, kRpdo,
     [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return static_cast<uint32_t>(o.device.target_ticks()); },
     [](const ObjectOwners& o, uint16_t, uint8_t, uint32_t v) -> uint32_t {
       o.device.set_target_ticks(static_cast<int32_t>(v));
       return 0;
     }},
    {od::kSoftwarePositionLimit, 0, 8, kNoPdo, [](const ObjectOwners&, uint16_t, uint8_t) -> uint32_t { return 2; }},
    {od::kSoftwarePositionLimit, 1, 32, kNoPdo,
     [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return static_cast<uint32_t>(o.device.limit_min_ticks()); },
     [](const ObjectOwners& o, uint16_t, uint8_t, uint32_t v) -> uint32_t {
       o.device.set_limit_min_ticks(static_cast<int32_t>(v));
       return 0;
     }},
    {od::kSoftwarePositionLimit, 2, 32, kNoPdo,
     [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return static_cast<uint32_t>(o.device.limit_max_ticks()); },
     [](const ObjectOwners& o, uint16_t, uint8_t, uint32_t v) -> uint32_t {
       o.device.set_limit_max_ticks(static_cast<int32_t>(v));
       return 0;
     }},
    // manufacturer objects (hand_drive_objects.h): the gains, REAL32 each
    {hand_od::kGains, 0, 8, kNoPdo, [](const ObjectOwners&, uint16_t, uint8_t) -> uint32_t { return hand_od::gain::kCount; }},
    {hand_od::kGains, 1, 32, kNoPdo, read_gain, write_gain},
    {hand_od::kGains, 2, 32, kNoPdo, read_gain, write_gain},
    {hand_od::kGains, 3, 32, kNoPdo, read_gain, write_gain},
    {hand_od::kGains, 4, 32, kNoPdo, read_gain, write_gain},
    {hand_od::kGains, 5, 32, kNoPdo, read_gain, write_gain},
    {hand_od::kGains, 6, 32, kNoPdo, read_gain, write_gain},
    {hand_od::kGains, 7, 32, kNoPdo, read_gain, write_gain},
    // ... and fault injection: reads return the setting (the fault's EMCY code for kRaiseFault)
    {hand_od::kFaultInjection, 0, 8, kNoPdo,
     [](const ObjectOwners&, uint16_t, uint8_t) -> uint32_t { return hand_od::inject::kCount; }},
    {hand_od::kFaultInjection, hand_od::inject::kSuppressHeartbeat, 32, kNoPdo,
     [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return o.faults.heartbeat_suppressed() ? 1 : 0; },
     [](const ObjectOwners& o, uint16_t, uint8_t, uint32_t v) -> uint32_t {
       o.faults.set_heartbeat_suppressed(v != 0);
       return 0;
     }},
    {hand_od::kFaultInjection, hand_od::inject::kRaiseFault, 32, kNoPdo,
     [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return o.device.error_code(); },
     [](const ObjectOwners& o, uint16_t, uint8_t, uint32_t v) -> uint32_t {
       if (v == 0 || v > 0xFFFF) return sdo_abort::kInvalidValue;
       o.device.raise_fault(static_cast<uint16_t>(v), {});
       return 0;
     }},
    {hand_od::kFaultInjection, hand_od::inject::kStall, 32, kNoPdo,
     [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return o.faults.stalled() ? 1 : 0; },
     [](const ObjectOwners& o, uint16_t, uint8_t, uint32_t v) -> uint32_t {
       o.faults.set_stalled(v != 0);
       return 0;
     }},
    {hand_od::kFaultInjection, hand_od::inject::kDropTpdos, 32, kNoPdo,
     [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return o.faults.tpdos_to_drop(); },
     [](const ObjectOwners& o, uint16_t, uint8_t, uint32_t v) -> uint32_t {
       o.faults.drop_tpdos(v);
       return 0;
     }},
    {hand_od::kFaultInjection, hand_od::inject::kRefuseSdo, 32, kNoPdo,
     [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return o.faults.sdo_refused() ? 1 : 0; },
     [](const ObjectOwners& o, uint16_t, uint8_t, uint32_t v) -> uint32_t {
       o.faults.set_sdo_refused(v != 0);
       return 0;
     }},
    {hand_od::kFaultInjection, hand_od::inject::kDropRpdos, 32, kNoPdo,
     [](const ObjectOwners& o, uint16_t, uint8_t) -> uint32_t { return o.faults.rpdos_to_drop(); },
     [](const ObjectOwners& o, uint16_t, uint8_t, uint32_t v) -> uint32_t {
       o.faults.drop_rpdos(v);
       return 0;
     }},
};

// --- the PDO parameters, the same for each channel: communication (0x1400 + n receive,
// 0x1800 + n transmit) and mapping (0x1600 + n, 0x1A00 + n) ---
bool transmit_side(uint16_t index) { return (index & 0x0800) != 0; }  // 0x18xx, 0x1Axx
size_t channel_of(uint16_t index) { return index & 0xFF; }

uint32_t read_communication(const ObjectOwners& o, uint16_t index, uint8_t subindex) {
  return o.pdos.communication(transmit_side(index), channel_of(index), subindex);
}
uint32_t write_communication(const ObjectOwners& o, uint16_t index, uint8_t subindex, uint32_t value) {
  return o.pdos.write_communication(transmit_side(index), channel_of(index), subindex, value, o.now_ns);
}
uint32_t read_mapping(const ObjectOwners& o, uint16_t index, uint8_t subindex) {
  return o.pdos.mapping(transmit_side(index), channel_of(index), subindex);
}
uint32_t write_mapping(const ObjectOwners& o, uint16_t index, uint8_t subindex, uint32_t value) {
  return o.pdos.write_mapping(transmit_side(index), channel_of(index), subindex, value);
}

struct PdoField {
  uint8_t subindex;
  uint8_t bits;
  bool writable;
};
// receive: highest subindex, COB-ID, transmission type; transmit adds inhibit time, event timer
constexpr PdoField kRpdoCommunication[] = {{0, 8, false}, {1, 32, true}, {2, 8, true}};
constexpr PdoField kTpdoCommunication[] = {{0, 8, false}, {1, 32, true}, {2, 8, true}, {3, 16, true}, {5, 16, true}};
constexpr size_t kMappingFields = 1 + can::PdoMapping::kMaxEntries;  // the count, then the entries
constexpr size_t kPdoObjects =
    PdoEngine::kChannels * (std::size(kRpdoCommunication) + std::size(kTpdoCommunication) + 2 * kMappingFields);

// the one table: the fixed objects, then every PDO parameter of every channel
constexpr auto kObjects = [] {
  std::array<ObjectEntry, std::size(kFixedObjects) + kPdoObjects> table{};
  size_t k = 0;
  for (const ObjectEntry& e : kFixedObjects) table[k++] = e;
  auto communication = [&](uint16_t index, const auto& fields) {
    for (const PdoField& f : fields) {
      table[k++] = {index, f.subindex, f.bits, kNoPdo, read_communication, f.writable ? write_communication : nullptr};
    }
  };
  auto mapping = [&](uint16_t index) {
    for (uint8_t s = 0; s < kMappingFields; ++s) {
      table[k++] = {index, s, static_cast<uint8_t>(s == 0 ? 8 : 32), kNoPdo, read_mapping, write_mapping};
    }
  };
  for (uint16_t n = 0; n < PdoEngine::kChannels; ++n) {
    communication(0x1400 + n, kRpdoCommunication);
    communication(0x1800 + n, kTpdoCommunication);
    mapping(0x1600 + n);
    mapping(0x1A00 + n);
  }
  return table;
}();

// the entry, or nullptr with the abort code: no such subindex of an existing object, or none
const ObjectEntry* lookup(uint16_t index, uint8_t subindex, uint32_t& abort) {
  bool index_exists = false;
  for (const ObjectEntry& e : kObjects) {
    if (e.index != index) continue;
    if (e.subindex == subindex) return &e;
    index_exists = true;
  }
  abort = index_exists ? sdo_abort::kNoSubindex : sdo_abort::kNoObject;
  return nullptr;
}

}  // namespace

uint32_t ObjectDictionary::find(uint16_t index, uint8_t subindex, ObjectInfo& info) {
  uint32_t abort = 0;
  const ObjectEntry* e = lookup(index, subindex, abort);
  if (e == nullptr) return abort;
  info = {e->bits, e->write != nullptr, e->pdo == kRpdo, e->pdo == kTpdo};
  return 0;
}

uint32_t ObjectDictionary::read(uint16_t index, uint8_t subindex, uint32_t& value) const {
  uint32_t abort = 0;
  const ObjectEntry* e = lookup(index, subindex, abort);
  if (e == nullptr) return abort;
  value = e->read(owners_, index, subindex);
  return 0;
}

uint32_t ObjectDictionary::write(uint16_t index, uint8_t subindex, uint32_t value) {
  uint32_t abort = 0;
  const ObjectEntry* e = lookup(index, subindex, abort);
  if (e == nullptr) return abort;
  if (e->write == nullptr) return sdo_abort::kReadOnly;
  return e->write(owners_, index, subindex, value);
}

}  // namespace teleop::hand::drive
