#pragma once
// CiA 301 (CANopen application layer) services on classic CAN frames, with the pre-defined
// connection set (COB-ID = function code + node id): NMT, SYNC, EMCY, heartbeat / boot-up,
// expedited SDO and PDOs with a mapping description.
//
// Every encoder checks its arguments and every decoder checks the COB-ID range, frame format,
// dlc and fields, returning a CanError instead of reading garbage. All functions are real-time
// safe: no heap, no exceptions.

#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <span>

#include "teleop/can/can_frame.h"

namespace teleop::can {

using NodeId = uint8_t;
constexpr NodeId kMaxNodeId = 127;
/// A device's node id: 1..127.
constexpr bool valid_node(NodeId node) { return node >= 1 && node <= kMaxNodeId; }

/// Function codes of the pre-defined connection set (COB-ID = code + node id).
namespace cob {
constexpr uint16_t kNmt = 0x000;
constexpr uint16_t kSync = 0x080;
constexpr uint16_t kEmcy = 0x080;
constexpr uint16_t kTpdo1 = 0x180;
constexpr uint16_t kRpdo1 = 0x200;
constexpr uint16_t kTpdo2 = 0x280;
constexpr uint16_t kRpdo2 = 0x300;
constexpr uint16_t kTpdo3 = 0x380;
constexpr uint16_t kRpdo3 = 0x400;
constexpr uint16_t kTpdo4 = 0x480;
constexpr uint16_t kRpdo4 = 0x500;
constexpr uint16_t kSdoTx = 0x580;  // server -> client (responses)
constexpr uint16_t kSdoRx = 0x600;  // client -> server (requests)
constexpr uint16_t kHeartbeat = 0x700;
}  // namespace cob

/// Communication objects of CiA 301 that masters and drives here write or serve.
namespace obj {
constexpr uint16_t kCommunicationCyclePeriod = 0x1006;  // UNSIGNED32 [us], the SYNC period
constexpr uint16_t kConsumerHeartbeatTime = 0x1016;     // sub n: UNSIGNED32 (node << 16) | ms
constexpr uint16_t kProducerHeartbeatTime = 0x1017;     // UNSIGNED16 [ms]
}  // namespace obj

/// An entry of the consumer heartbeat time (0x1016 sub n): watch `node`'s heartbeat, `ms` at most
/// between two (0 or node 0: the entry is off).
constexpr uint32_t consumer_heartbeat_entry(uint8_t node, uint16_t ms) {
  return (static_cast<uint32_t>(node) << 16) | ms;
}

/// Default COB-ID of TPDO n (1..4) of a node: 0x180/0x280/0x380/0x480 + node.
constexpr uint16_t tpdo_cob_id(unsigned n, NodeId node) { return static_cast<uint16_t>(0x080 + 0x100 * n + node); }
/// Default COB-ID of RPDO n (1..4) of a node: 0x200/0x300/0x400/0x500 + node.
constexpr uint16_t rpdo_cob_id(unsigned n, NodeId node) { return static_cast<uint16_t>(0x100 + 0x100 * n + node); }

/// What a frame is under the pre-defined connection set, e.g. for a bus monitor.
enum class Service : uint8_t { kUnknown, kNmt, kSync, kEmcy, kTpdo, kRpdo, kSdoResponse, kSdoRequest, kHeartbeat };
struct ServiceId {
  Service service = Service::kUnknown;
  NodeId node = 0;         // 0 for NMT and SYNC
  uint8_t pdo_number = 0;  // 1..4 for PDOs
};
/// Classifies a frame by its COB-ID (no payload checks). Extended, RTR and error frames are kUnknown.
ServiceId classify(const CanFrame& frame);
const char* to_string(Service service);

// ---------------------------------------------------------------------------------------------
// NMT (COB-ID 0x000, 2 bytes: command specifier, node id or 0 for all nodes)

enum class NmtCommand : uint8_t {
  kStart = 0x01,
  kStop = 0x02,
  kEnterPreOperational = 0x80,
  kResetNode = 0x81,
  kResetCommunication = 0x82,
};
struct NmtMessage {
  NmtCommand command = NmtCommand::kStart;
  NodeId node = 0;  // 0 = all nodes
};
/// node: 0 (broadcast) or 1..127.
Result<CanFrame> encode_nmt(NmtCommand command, NodeId node);
Result<NmtMessage> decode_nmt(const CanFrame& frame);

// ---------------------------------------------------------------------------------------------
// SYNC (COB-ID 0x080, no data or one counter byte 1..240)

constexpr uint8_t kMaxSyncCounter = 240;
struct SyncMessage {
  uint8_t counter = 0;  // 0 = the SYNC carried no counter
};
/// counter 0 sends a SYNC without data; 1..240 with the counter byte.
Result<CanFrame> encode_sync(uint8_t counter = 0);
Result<SyncMessage> decode_sync(const CanFrame& frame);

// ---------------------------------------------------------------------------------------------
// EMCY (COB-ID 0x080 + node, 8 bytes: error code, error register 0x1001, 5 vendor bytes)

/// Emergency error codes used here (CiA 301 classes, CiA 402 drive codes).
namespace emcy {
constexpr uint16_t kErrorReset = 0x0000;  // error cleared / no error
constexpr uint16_t kGeneric = 0x1000;
constexpr uint16_t kCurrent = 0x2000;
constexpr uint16_t kOverCurrent = 0x2310;  // continuous over-current, output side
constexpr uint16_t kVoltage = 0x3000;
constexpr uint16_t kTemperature = 0x4000;
constexpr uint16_t kDeviceHardware = 0x5000;
constexpr uint16_t kSoftware = 0x6000;
constexpr uint16_t kMotorBlocked = 0x7121;
constexpr uint16_t kSensor = 0x7300;
constexpr uint16_t kCommunication = 0x8100;
constexpr uint16_t kCanOverrun = 0x8110;
constexpr uint16_t kCanErrorPassive = 0x8120;
constexpr uint16_t kHeartbeatError = 0x8130;
constexpr uint16_t kRecoveredFromBusOff = 0x8140;
constexpr uint16_t kPdoLengthError = 0x8210;     // PDO not processed due to length error
constexpr uint16_t kPdoLengthExceeded = 0x8220;  // PDO longer than its mapping
constexpr uint16_t kFollowingError = 0x8611;
}  // namespace emcy

/// Bits of the error register (object 0x1001, byte 2 of every EMCY).
namespace error_register {
constexpr uint8_t kGeneric = 0x01;
constexpr uint8_t kCurrent = 0x02;
constexpr uint8_t kVoltage = 0x04;
constexpr uint8_t kTemperature = 0x08;
constexpr uint8_t kCommunication = 0x10;
constexpr uint8_t kDeviceProfile = 0x20;
constexpr uint8_t kManufacturer = 0x80;
}  // namespace error_register
/// The error register a device reports with an error code: the generic bit plus the class bit
/// (current, voltage, temperature, communication, device profile for 0x7xxx/0x86xx); 0 for 0x0000.
uint8_t error_register_for(uint16_t error_code);

struct EmcyMessage {
  NodeId node = 0;
  uint16_t error_code = 0;
  uint8_t error_register = 0;
  std::array<uint8_t, 5> vendor{};
};
Result<CanFrame> encode_emcy(const EmcyMessage& message);
/// Requires COB-ID 0x081..0x0FF and dlc 8.
Result<EmcyMessage> decode_emcy(const CanFrame& frame);

// ---------------------------------------------------------------------------------------------
// Heartbeat and boot-up (COB-ID 0x700 + node, 1 byte: NMT state; boot-up is state 0)

enum class NmtState : uint8_t {
  kBootUp = 0x00,  // also: initialising
  kStopped = 0x04,
  kOperational = 0x05,
  kPreOperational = 0x7F,
};
const char* to_string(NmtState state);
struct HeartbeatMessage {
  NodeId node = 0;
  NmtState state = NmtState::kBootUp;
};
Result<CanFrame> encode_heartbeat(NodeId node, NmtState state);
/// Requires dlc 1 and one of the four state values (the node-guarding toggle bit must be 0).
Result<HeartbeatMessage> decode_heartbeat(const CanFrame& frame);

// ---------------------------------------------------------------------------------------------
// SDO, expedited transfers only (requests 0x600 + node, responses 0x580 + node, always 8 bytes)

/// SDO abort codes (CiA 301).
namespace sdo_abort {
constexpr uint32_t kToggleBit = 0x05030000;
constexpr uint32_t kTimeout = 0x05040000;
constexpr uint32_t kInvalidCommand = 0x05040001;
constexpr uint32_t kOutOfMemory = 0x05040005;
constexpr uint32_t kUnsupportedAccess = 0x06010000;
constexpr uint32_t kWriteOnly = 0x06010001;  // read of a write-only object
constexpr uint32_t kReadOnly = 0x06010002;   // write of a read-only object
constexpr uint32_t kNoObject = 0x06020000;
constexpr uint32_t kNotMappable = 0x06040041;
constexpr uint32_t kMappingTooLong = 0x06040042;
constexpr uint32_t kParameterIncompatible = 0x06040043;
constexpr uint32_t kHardware = 0x06060000;
constexpr uint32_t kLengthMismatch = 0x06070010;
constexpr uint32_t kLengthTooHigh = 0x06070012;
constexpr uint32_t kLengthTooLow = 0x06070013;
constexpr uint32_t kNoSubindex = 0x06090011;
constexpr uint32_t kInvalidValue = 0x06090030;
constexpr uint32_t kValueTooHigh = 0x06090031;
constexpr uint32_t kValueTooLow = 0x06090032;
constexpr uint32_t kGeneral = 0x08000000;
constexpr uint32_t kCannotStore = 0x08000020;
constexpr uint32_t kLocalControl = 0x08000021;
constexpr uint32_t kDeviceState = 0x08000022;
}  // namespace sdo_abort

/// Command specifier bytes of expedited SDO (byte 0).
namespace sdo_cs {
constexpr uint8_t kDownloadRequest = 0x20;   // ccs 1 | n << 2 | e | s
constexpr uint8_t kUploadRequest = 0x40;     // ccs 2
constexpr uint8_t kUploadResponse = 0x40;    // scs 2 | n << 2 | e | s
constexpr uint8_t kDownloadResponse = 0x60;  // scs 3
constexpr uint8_t kAbort = 0x80;             // cs 4
constexpr uint8_t kExpedited = 0x02;
constexpr uint8_t kSizeIndicated = 0x01;
}  // namespace sdo_cs

enum class SdoType : uint8_t {
  kDownloadRequest,   // client writes an object
  kUploadRequest,     // client reads an object
  kDownloadResponse,  // server confirms a write
  kUploadResponse,    // server returns the value read
  kAbort,             // either side aborts the transfer
};
struct SdoMessage {
  NodeId node = 0;  // the server's node id
  SdoType type = SdoType::kUploadRequest;
  uint16_t index = 0;
  uint8_t subindex = 0;
  uint32_t data = 0;        // value of download requests and upload responses, little-endian
  uint8_t size = 0;         // data bytes 1..4; 0 = size not indicated (treat as up to 4)
  uint32_t abort_code = 0;  // for kAbort
};

/// size: 1..4 bytes, `value` must fit in them.
Result<CanFrame> encode_sdo_download_request(NodeId node, uint16_t index, uint8_t subindex, uint32_t value,
                                             uint8_t size);
Result<CanFrame> encode_sdo_upload_request(NodeId node, uint16_t index, uint8_t subindex);
Result<CanFrame> encode_sdo_download_response(NodeId node, uint16_t index, uint8_t subindex);
/// size: 1..4 bytes, `value` must fit in them.
Result<CanFrame> encode_sdo_upload_response(NodeId node, uint16_t index, uint8_t subindex, uint32_t value,
                                            uint8_t size);
/// An abort from the server (`from_server`, COB-ID 0x580 + node) or from the client (0x600 + node).
Result<CanFrame> encode_sdo_abort(NodeId node, uint16_t index, uint8_t subindex, uint32_t abort_code, bool from_server);
/// Decodes a client request (COB-ID 0x601..0x67F): download, upload or abort. Segmented and
/// block transfers are kUnsupported (a server answers them with abort kInvalidCommand or
/// kUnsupportedAccess); unknown specifiers and set reserved bits are kInvalidCommand.
Result<SdoMessage> decode_sdo_request(const CanFrame& frame);
/// Decodes a server response (COB-ID 0x581..0x5FF): download ack, upload data or abort.
Result<SdoMessage> decode_sdo_response(const CanFrame& frame);

// ---------------------------------------------------------------------------------------------
// PDO: payload packed from a mapping description

/// One mapped object: index, subindex and length in bits, as written in the mapping objects
/// 0x1600.. / 0x1A00.. ((index << 16) | (subindex << 8) | bits). Index 0x0001..0x0007 are
/// "dummy" entries (the data types) that skip bits of a received PDO.
struct PdoMapEntry {
  uint16_t index = 0;
  uint8_t subindex = 0;
  uint8_t bits = 0;

  constexpr uint32_t to_u32() const {
    return (static_cast<uint32_t>(index) << 16) | (static_cast<uint32_t>(subindex) << 8) | bits;
  }
  static constexpr PdoMapEntry from_u32(uint32_t v) {
    return {static_cast<uint16_t>(v >> 16), static_cast<uint8_t>(v >> 8), static_cast<uint8_t>(v)};
  }
  constexpr bool dummy() const { return index >= 0x0001 && index <= 0x0007; }
  friend constexpr bool operator==(const PdoMapEntry&, const PdoMapEntry&) = default;
};

/// Dummy mapping entries (skip 8/16/32 bits in an RPDO shared by several nodes).
constexpr PdoMapEntry kDummy8{0x0005, 0, 8};
constexpr PdoMapEntry kDummy16{0x0006, 0, 16};
constexpr PdoMapEntry kDummy32{0x0007, 0, 32};

/// Up to 8 entries, at most 64 bits, packed little-endian from bit 0 in order.
class PdoMapping {
 public:
  static constexpr size_t kMaxEntries = 8;
  static constexpr unsigned kMaxBits = 64;

  PdoMapping() = default;
  /// Builds a mapping; fails as add() does.
  static Result<PdoMapping> make(std::initializer_list<PdoMapEntry> entries);

  /// Appends an entry: kInvalidMapping for 0 or more than 64 bits or a ninth entry,
  /// kMappingTooLong when the total would exceed 64 bits.
  CanError add(const PdoMapEntry& entry);
  void clear() {
    count_ = 0;
    bits_ = 0;
  }

  size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  const PdoMapEntry& operator[](size_t i) const { return entries_[i]; }
  unsigned total_bits() const { return bits_; }
  /// Payload bytes: total bits rounded up to whole bytes.
  uint8_t dlc() const { return static_cast<uint8_t>((bits_ + 7) / 8); }
  /// Bit offset of entry i in the payload.
  unsigned offset_bits(size_t i) const;

  friend bool operator==(const PdoMapping& a, const PdoMapping& b);

 private:
  std::array<PdoMapEntry, kMaxEntries> entries_{};
  uint8_t count_ = 0;
  uint8_t bits_ = 0;
};

/// Packs one raw value per mapping entry (two's complement for signed objects; each value is
/// truncated to its entry's width, dummy entries send zeros) into a frame of mapping.dlc() bytes.
/// values.size() must equal mapping.size(); cob_id must be an 11-bit id.
Result<CanFrame> encode_pdo(uint16_t cob_id, const PdoMapping& mapping, std::span<const uint64_t> values);
/// Unpacks a PDO into one raw value per entry (dummy entries read as 0). Fails for RTR,
/// extended or error frames, a dlc shorter than the mapping (CiA 301: EMCY 0x8210), or
/// values.size() != mapping.size(). A longer dlc is accepted (the extra bytes are ignored).
CanError decode_pdo(const CanFrame& frame, const PdoMapping& mapping, std::span<uint64_t> values);
/// Interprets the low `bits` bits of raw as a two's complement number.
int64_t sign_extend(uint64_t raw, unsigned bits);

}  // namespace teleop::can
