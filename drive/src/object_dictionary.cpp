#include "object_dictionary.h"

#include <array>
#include <cmath>

#include "teleop/can/cia301.h"
#include "teleop/can/cia402.h"
#include "teleop/drive/drive_objects.h"

namespace teleop::drive {

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

// --- readers and writers shared by several objects ---

template <uint32_t Value>
uint32_t constant(const ObjectOwners&, uint16_t, uint8_t) {
  return Value;
}

// a CiA 402 object of the device side: read through its getter, written as the object's type T
template <auto Get>
uint32_t device_value(const ObjectOwners& o, uint16_t, uint8_t) {
  return static_cast<uint32_t>((o.device.*Get)());
}
template <typename T, void (Cia402Device::*Set)(T)>
uint32_t set_device_value(const ObjectOwners& o, uint16_t, uint8_t, uint32_t value) {
  (o.device.*Set)(static_cast<T>(value));
  return 0;
}

template <uint32_t EmulatedDriveConfig::*Field>
uint32_t identity(const ObjectOwners& o, uint16_t, uint8_t) {
  return o.config.*Field;
}

// fault injection: switches (0 off, anything else on) and counts of PDOs to drop
template <bool (FaultInjection::*Get)() const>
uint32_t injection_switch(const ObjectOwners& o, uint16_t, uint8_t) {
  return (o.faults.*Get)() ? 1 : 0;
}
template <void (FaultInjection::*Set)(bool)>
uint32_t set_injection_switch(const ObjectOwners& o, uint16_t, uint8_t, uint32_t value) {
  (o.faults.*Set)(value != 0);
  return 0;
}
template <uint32_t (FaultInjection::*Get)() const>
uint32_t injection_count(const ObjectOwners& o, uint16_t, uint8_t) {
  return (o.faults.*Get)();
}
template <void (FaultInjection::*Set)(uint32_t)>
uint32_t set_injection_count(const ObjectOwners& o, uint16_t, uint8_t, uint32_t value) {
  (o.faults.*Set)(value);
  return 0;
}

// --- objects with a rule of their own ---

// producer heartbeat time [ms]; a write restarts the heartbeat timer
uint32_t heartbeat_time(const ObjectOwners& o, uint16_t, uint8_t) { return o.nmt.heartbeat_ms(); }
uint32_t set_heartbeat_time(const ObjectOwners& o, uint16_t, uint8_t, uint32_t value) {
  o.nmt.set_heartbeat_ms(static_cast<uint16_t>(value), o.now_ns);
  return 0;
}

// consumer heartbeat time, sub 1..HeartbeatConsumer::kEntries
uint32_t consumer_heartbeat(const ObjectOwners& o, uint16_t, uint8_t subindex) {
  return o.heartbeats.entry(subindex);
}
uint32_t set_consumer_heartbeat(const ObjectOwners& o, uint16_t, uint8_t subindex, uint32_t value) {
  return o.heartbeats.set_entry(subindex, value);
}

// the abort connection option code: INTEGER16, carried as its 16 bits
uint32_t abort_connection_option(const ObjectOwners& o, uint16_t, uint8_t) {
  return static_cast<uint16_t>(o.device.abort_connection_option());
}
uint32_t set_abort_connection_option(const ObjectOwners& o, uint16_t, uint8_t, uint32_t value) {
  return o.device.set_abort_connection_option(static_cast<int16_t>(value)) ? 0 : sdo_abort::kInvalidValue;
}

// quick stop option code: the drive brakes with its position loop and stays in quick stop active
// (code 6), which is all it can do; writing that is accepted, anything else refused
uint32_t quick_stop_option(const ObjectOwners&, uint16_t, uint8_t) {
  return static_cast<uint16_t>(can::cia402::kQuickStopRampAndHold);
}
uint32_t set_quick_stop_option(const ObjectOwners&, uint16_t, uint8_t, uint32_t value) {
  return static_cast<int16_t>(value) == can::cia402::kQuickStopRampAndHold ? 0 : sdo_abort::kInvalidValue;
}

// modes of operation (and its display): INTEGER8, carried as its 8 bits
uint32_t mode(const ObjectOwners& o, uint16_t, uint8_t) { return static_cast<uint8_t>(o.device.mode()); }
uint32_t set_mode(const ObjectOwners& o, uint16_t, uint8_t, uint32_t value) {
  return o.device.set_mode(static_cast<int8_t>(static_cast<uint8_t>(value))) ? 0 : sdo_abort::kInvalidValue;
}

uint32_t position_actual(const ObjectOwners& o, uint16_t, uint8_t) {
  return static_cast<uint32_t>(o.motor.encoder_ticks());
}
uint32_t velocity_actual(const ObjectOwners& o, uint16_t, uint8_t) {
  return static_cast<uint32_t>(saturate_int32(o.servo.velocity_estimate_radps() * o.motor.ticks_per_rad()));
}
uint32_t current_actual(const ObjectOwners& o, uint16_t, uint8_t) {
  return static_cast<uint16_t>(saturate_int16(o.motor.current_a() / o.config.rated_current_a * 1e3));
}
// a DC motor's torque, k_t x current, per mille of the rated torque 0x6076
uint32_t torque_actual(const ObjectOwners& o, uint16_t, uint8_t) {
  const double torque_mnm = o.config.motor.torque_constant_nm_per_a * o.motor.current_a() * 1e3;
  return static_cast<uint16_t>(saturate_int16(torque_mnm / o.device.rated_torque_mnm() * 1e3));
}
// target torque: INTEGER16, carried as its 16 bits
uint32_t target_torque(const ObjectOwners& o, uint16_t, uint8_t) {
  return static_cast<uint16_t>(o.device.target_torque_permille());
}
uint32_t rated_current(const ObjectOwners& o, uint16_t, uint8_t) {
  return static_cast<uint32_t>(std::lround(o.config.rated_current_a * 1e3));
}
uint32_t set_max_current(const ObjectOwners& o, uint16_t, uint8_t, uint32_t value) {
  return o.device.set_max_current_permille(static_cast<uint16_t>(value)) ? 0 : sdo_abort::kValueTooHigh;
}

// the controller parameter behind each subindex 1.. of the gains object (REAL32 each)
constexpr double EmulatedControllerParams::*kGainSlots[drive_od::gain::kCount] = {
    &EmulatedControllerParams::position_kp_a_per_rad,        &EmulatedControllerParams::position_ki_a_per_rad_s,
    &EmulatedControllerParams::position_kd_a_s_per_rad,      &EmulatedControllerParams::position_integral_limit_a,
    &EmulatedControllerParams::max_reference_velocity_radps, &EmulatedControllerParams::current_kp_v_per_a,
    &EmulatedControllerParams::current_ki_v_per_a_s};

uint32_t gain(const ObjectOwners& o, uint16_t, uint8_t subindex) {
  return drive_od::real32_bits(o.config.control.*kGainSlots[subindex - 1]);
}
uint32_t set_gain(const ObjectOwners& o, uint16_t, uint8_t subindex, uint32_t value) {
  const double gain = drive_od::real32_value(value);
  if (!std::isfinite(gain)) return sdo_abort::kInvalidValue;
  if (gain < 0) return sdo_abort::kValueTooLow;
  // the reference step limit must stay positive, or the reference could never move
  if (subindex == drive_od::gain::kMaxReferenceVelocity && gain <= 0) return sdo_abort::kValueTooLow;
  o.config.control.*kGainSlots[subindex - 1] = gain;
  return 0;
}

// a fault with this EMCY code now; reading gives the code in force
uint32_t raise_fault(const ObjectOwners& o, uint16_t, uint8_t, uint32_t value) {
  if (value == 0 || value > 0xFFFF) return sdo_abort::kInvalidValue;
  o.device.raise_fault(static_cast<uint16_t>(value), {});
  return 0;
}

using D = Cia402Device;
using F = FaultInjection;
namespace inject = drive_od::inject;

// the fixed objects (subindex 0 unless noted); the gains and the PDO parameters, alike per
// subindex or channel, are added to the table below
constexpr ObjectEntry kFixedObjects[] = {
    {0x1000, 0, 32, kNoPdo, constant<EmulatedDrive::kDeviceType>},  // device type
    {0x1001, 0, 8, kTpdo, device_value<&D::error_register>},
    {can::obj::kConsumerHeartbeatTime, 0, 8, kNoPdo, constant<HeartbeatConsumer::kEntries>},
    {can::obj::kConsumerHeartbeatTime, 1, 32, kNoPdo, consumer_heartbeat, set_consumer_heartbeat},
    {can::obj::kConsumerHeartbeatTime, 2, 32, kNoPdo, consumer_heartbeat, set_consumer_heartbeat},
    {can::obj::kProducerHeartbeatTime, 0, 16, kNoPdo, heartbeat_time, set_heartbeat_time},
    // identity: highest subindex, vendor id, product code, revision, serial number
    {0x1018, 0, 8, kNoPdo, constant<4>},
    {0x1018, 1, 32, kNoPdo, identity<&EmulatedDriveConfig::vendor_id>},
    {0x1018, 2, 32, kNoPdo, identity<&EmulatedDriveConfig::product_code>},
    {0x1018, 3, 32, kNoPdo, identity<&EmulatedDriveConfig::revision>},
    {0x1018, 4, 32, kNoPdo, identity<&EmulatedDriveConfig::serial>},
    // CiA 402
    {od::kAbortConnectionOptionCode, 0, 16, kNoPdo, abort_connection_option, set_abort_connection_option},
    {od::kErrorCode, 0, 16, kTpdo, device_value<&D::error_code>},
    {od::kControlword, 0, 16, kRpdo, device_value<&D::controlword>, set_device_value<uint16_t, &D::set_controlword>},
    {od::kStatusword, 0, 16, kTpdo, device_value<&D::statusword>},
    {od::kModesOfOperation, 0, 8, kRpdo, mode, set_mode},
    {od::kModesOfOperationDisplay, 0, 8, kTpdo, mode},
    {od::kQuickStopOptionCode, 0, 16, kNoPdo, quick_stop_option, set_quick_stop_option},
    {od::kPositionActualValue, 0, 32, kTpdo, position_actual},
    {od::kFollowingErrorWindow, 0, 32, kNoPdo, device_value<&D::following_error_window_ticks>,
     set_device_value<uint32_t, &D::set_following_error_window_ticks>},
    {od::kFollowingErrorTimeout, 0, 16, kNoPdo, device_value<&D::following_error_timeout_ms>,
     set_device_value<uint16_t, &D::set_following_error_timeout_ms>},
    {od::kVelocityActualValue, 0, 32, kTpdo, velocity_actual},
    {od::kTargetTorque, 0, 16, kRpdo, target_torque, set_device_value<int16_t, &D::set_target_torque_permille>},
    {od::kMaxCurrent, 0, 16, kRpdo, device_value<&D::max_current_permille>, set_max_current},
    {od::kMotorRatedCurrent, 0, 32, kNoPdo, rated_current},
    {od::kMotorRatedTorque, 0, 32, kNoPdo, device_value<&D::rated_torque_mnm>},
    {od::kTorqueActualValue, 0, 16, kTpdo, torque_actual},
    {od::kCurrentActualValue, 0, 16, kTpdo, current_actual},
    {od::kTargetPosition, 0, 32, kRpdo, device_value<&D::target_ticks>,
     set_device_value<int32_t, &D::set_target_ticks>},
    {od::kSoftwarePositionLimit, 0, 8, kNoPdo, constant<2>},
    {od::kSoftwarePositionLimit, 1, 32, kNoPdo, device_value<&D::limit_min_ticks>,
     set_device_value<int32_t, &D::set_limit_min_ticks>},
    {od::kSoftwarePositionLimit, 2, 32, kNoPdo, device_value<&D::limit_max_ticks>,
     set_device_value<int32_t, &D::set_limit_max_ticks>},
    // manufacturer objects (drive_objects.h): the gains' count (the gains follow below) ...
    {drive_od::kGains, 0, 8, kNoPdo, constant<drive_od::gain::kCount>},
    // ... and fault injection: reads return the setting (the fault's EMCY code for kRaiseFault)
    {drive_od::kFaultInjection, 0, 8, kNoPdo, constant<inject::kCount>},
    {drive_od::kFaultInjection, inject::kSuppressHeartbeat, 32, kNoPdo, injection_switch<&F::heartbeat_suppressed>,
     set_injection_switch<&F::set_heartbeat_suppressed>},
    {drive_od::kFaultInjection, inject::kRaiseFault, 32, kNoPdo, device_value<&D::error_code>, raise_fault},
    {drive_od::kFaultInjection, inject::kStall, 32, kNoPdo, injection_switch<&F::stalled>,
     set_injection_switch<&F::set_stalled>},
    {drive_od::kFaultInjection, inject::kDropTpdos, 32, kNoPdo, injection_count<&F::tpdos_to_drop>,
     set_injection_count<&F::drop_tpdos>},
    {drive_od::kFaultInjection, inject::kRefuseSdo, 32, kNoPdo, injection_switch<&F::sdo_refused>,
     set_injection_switch<&F::set_sdo_refused>},
    {drive_od::kFaultInjection, inject::kDropRpdos, 32, kNoPdo, injection_count<&F::rpdos_to_drop>,
     set_injection_count<&F::drop_rpdos>},
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
constexpr size_t kGainObjects = drive_od::gain::kCount;

// the one table: the fixed objects, the gains, then every PDO parameter of every channel
constexpr auto kObjects = [] {
  std::array<ObjectEntry, std::size(kFixedObjects) + kGainObjects + kPdoObjects> table{};
  size_t k = 0;
  for (const ObjectEntry& e : kFixedObjects) table[k++] = e;
  for (uint8_t s = 1; s <= drive_od::gain::kCount; ++s) table[k++] = {drive_od::kGains, s, 32, kNoPdo, gain, set_gain};
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

}  // namespace teleop::drive
