#include "teleop/can/cia301.h"

namespace teleop::can {
namespace {

// a decoder's first check: a classic data frame with an 11-bit id
CanError check_data_frame(const CanFrame& frame) {
  if (frame.error()) return CanError::kErrorFrame;
  if (frame.extended()) return CanError::kExtendedFrame;
  if (frame.rtr()) return CanError::kRemoteFrame;
  // flag bits the frame type does not have (never from SocketCAN; found by the fuzzer)
  if ((frame.flags & ~(CanFrame::kRtr | CanFrame::kExtended | CanFrame::kError)) != 0) return CanError::kInvalidField;
  if (frame.dlc > CanFrame::kMaxDlc || frame.id > CanFrame::kMaxStandardId) return CanError::kInvalidDlc;
  return CanError::kNone;
}

CanFrame make_frame(uint32_t id, uint8_t dlc) {
  CanFrame frame;
  frame.id = id;
  frame.dlc = dlc;
  return frame;
}

bool fits(uint32_t value, uint8_t size) { return size >= 4 || (value >> (8 * size)) == 0; }

uint32_t truncate(uint32_t value, uint8_t size) {
  return size >= 4 || size == 0 ? value : value & ((1u << (8 * size)) - 1);
}

uint64_t mask_bits(unsigned bits) { return bits >= 64 ? ~uint64_t{0} : (uint64_t{1} << bits) - 1; }

// expedited initiate frame: specifier, index, subindex, 4 data bytes
CanFrame sdo_frame(uint32_t id, uint8_t cs, uint16_t index, uint8_t subindex, uint32_t data) {
  CanFrame frame = make_frame(id, 8);
  frame.data[0] = cs;
  le::put_u16(&frame.data[1], index);
  frame.data[3] = subindex;
  le::put_u32(&frame.data[4], data);
  return frame;
}

uint8_t expedited_cs(uint8_t base, uint8_t size) {
  return static_cast<uint8_t>(base | ((4 - size) << 2) | sdo_cs::kExpedited | sdo_cs::kSizeIndicated);
}

// the e/s/n bits of an expedited initiate download request or upload response
CanError decode_expedited(uint8_t cs, SdoMessage& out) {
  if (cs & 0x10) return CanError::kInvalidCommand;                // reserved bit
  if (!(cs & sdo_cs::kExpedited)) return CanError::kUnsupported;  // segmented transfer
  const uint8_t n = (cs >> 2) & 0x03;
  if (cs & sdo_cs::kSizeIndicated) {
    out.size = static_cast<uint8_t>(4 - n);
  } else {
    if (n != 0) return CanError::kInvalidCommand;  // n only has a meaning with s = 1
    out.size = 0;
  }
  out.data = truncate(out.data, out.size);
  return CanError::kNone;
}

}  // namespace

// ---------------------------------------------------------------------------------------------

ServiceId classify(const CanFrame& frame) {
  if (frame.error() || frame.extended() || frame.rtr() || frame.id > CanFrame::kMaxStandardId) return {};
  const unsigned function = frame.id >> 7;
  const auto node = static_cast<NodeId>(frame.id & 0x7F);
  if (function == 0) return node == 0 ? ServiceId{Service::kNmt, 0, 0} : ServiceId{};
  if (function == 1) return node == 0 ? ServiceId{Service::kSync, 0, 0} : ServiceId{Service::kEmcy, node, 0};
  if (node == 0) return {};
  if (function >= 3 && function <= 10) {
    const auto number = static_cast<uint8_t>((function - 1) / 2);
    return {function % 2 == 1 ? Service::kTpdo : Service::kRpdo, node, number};
  }
  if (function == 11) return {Service::kSdoResponse, node, 0};
  if (function == 12) return {Service::kSdoRequest, node, 0};
  if (function == 14) return {Service::kHeartbeat, node, 0};
  return {};
}

const char* to_string(Service service) {
  switch (service) {
    case Service::kUnknown:
      return "unknown";
    case Service::kNmt:
      return "nmt";
    case Service::kSync:
      return "sync";
    case Service::kEmcy:
      return "emcy";
    case Service::kTpdo:
      return "tpdo";
    case Service::kRpdo:
      return "rpdo";
    case Service::kSdoResponse:
      return "sdo-rx";
    case Service::kSdoRequest:
      return "sdo-tx";
    case Service::kHeartbeat:
      return "heartbeat";
  }
  return "unknown";
}

// ---------------------------------------------------------------------------------------------
// NMT

namespace {
bool valid_nmt_command(uint8_t cs) {
  switch (static_cast<NmtCommand>(cs)) {
    case NmtCommand::kStart:
    case NmtCommand::kStop:
    case NmtCommand::kEnterPreOperational:
    case NmtCommand::kResetNode:
    case NmtCommand::kResetCommunication:
      return true;
  }
  return false;
}
}  // namespace

Result<CanFrame> encode_nmt(NmtCommand command, NodeId node) {
  if (!valid_nmt_command(static_cast<uint8_t>(command))) return CanError::kInvalidCommand;
  if (node > kMaxNodeId) return CanError::kInvalidNode;
  CanFrame frame = make_frame(cob::kNmt, 2);
  frame.data[0] = static_cast<uint8_t>(command);
  frame.data[1] = node;
  return frame;
}

Result<NmtMessage> decode_nmt(const CanFrame& frame) {
  if (const CanError e = check_data_frame(frame); e != CanError::kNone) return e;
  if (frame.id != cob::kNmt) return CanError::kInvalidId;
  if (frame.dlc != 2) return CanError::kInvalidDlc;
  if (!valid_nmt_command(frame.data[0])) return CanError::kInvalidCommand;
  if (frame.data[1] > kMaxNodeId) return CanError::kInvalidNode;
  return NmtMessage{static_cast<NmtCommand>(frame.data[0]), frame.data[1]};
}

// ---------------------------------------------------------------------------------------------
// SYNC

Result<CanFrame> encode_sync(uint8_t counter) {
  if (counter > kMaxSyncCounter) return CanError::kValueOutOfRange;
  CanFrame frame = make_frame(cob::kSync, counter == 0 ? 0 : 1);
  frame.data[0] = counter;
  return frame;
}

Result<SyncMessage> decode_sync(const CanFrame& frame) {
  if (const CanError e = check_data_frame(frame); e != CanError::kNone) return e;
  if (frame.id != cob::kSync) return CanError::kInvalidId;
  if (frame.dlc == 0) return SyncMessage{0};
  if (frame.dlc != 1) return CanError::kInvalidDlc;
  if (frame.data[0] == 0 || frame.data[0] > kMaxSyncCounter) return CanError::kInvalidField;
  return SyncMessage{frame.data[0]};
}

// ---------------------------------------------------------------------------------------------
// EMCY

uint8_t error_register_for(uint16_t error_code) {
  if (error_code == emcy::kErrorReset) return 0;
  uint8_t reg = error_register::kGeneric;
  switch (error_code >> 12) {
    case 0x2:
      reg |= error_register::kCurrent;
      break;
    case 0x3:
      reg |= error_register::kVoltage;
      break;
    case 0x4:
      reg |= error_register::kTemperature;
      break;
    case 0x7:
      reg |= error_register::kDeviceProfile;
      break;  // motor / sensor (CiA 402)
    case 0x8:
      // 0x81xx communication, 0x82xx protocol; 0x84xx..0x86xx are drive monitoring (CiA 402)
      reg |= ((error_code >> 8) & 0x0F) <= 0x2 ? error_register::kCommunication : error_register::kDeviceProfile;
      break;
    case 0xF:
      reg |= error_register::kManufacturer;
      break;
    default:
      break;
  }
  return reg;
}

Result<CanFrame> encode_emcy(const EmcyMessage& message) {
  if (!valid_node(message.node)) return CanError::kInvalidNode;
  CanFrame frame = make_frame(cob::kEmcy + message.node, 8);
  le::put_u16(&frame.data[0], message.error_code);
  frame.data[2] = message.error_register;
  for (size_t i = 0; i < message.vendor.size(); ++i) frame.data[3 + i] = message.vendor[i];
  return frame;
}

Result<EmcyMessage> decode_emcy(const CanFrame& frame) {
  if (const CanError e = check_data_frame(frame); e != CanError::kNone) return e;
  if (frame.id <= cob::kEmcy || frame.id > cob::kEmcy + kMaxNodeId) return CanError::kInvalidId;
  if (frame.dlc != 8) return CanError::kInvalidDlc;
  EmcyMessage message;
  message.node = static_cast<NodeId>(frame.id - cob::kEmcy);
  message.error_code = le::get_u16(&frame.data[0]);
  message.error_register = frame.data[2];
  for (size_t i = 0; i < message.vendor.size(); ++i) message.vendor[i] = frame.data[3 + i];
  return message;
}

// ---------------------------------------------------------------------------------------------
// Heartbeat

namespace {
bool valid_nmt_state(uint8_t s) {
  switch (static_cast<NmtState>(s)) {
    case NmtState::kBootUp:
    case NmtState::kStopped:
    case NmtState::kOperational:
    case NmtState::kPreOperational:
      return true;
  }
  return false;
}
}  // namespace

const char* to_string(NmtState state) {
  switch (state) {
    case NmtState::kBootUp:
      return "boot-up";
    case NmtState::kStopped:
      return "stopped";
    case NmtState::kOperational:
      return "operational";
    case NmtState::kPreOperational:
      return "pre-operational";
  }
  return "unknown";
}

Result<CanFrame> encode_heartbeat(NodeId node, NmtState state) {
  if (!valid_node(node)) return CanError::kInvalidNode;
  if (!valid_nmt_state(static_cast<uint8_t>(state))) return CanError::kInvalidField;
  CanFrame frame = make_frame(cob::kHeartbeat + node, 1);
  frame.data[0] = static_cast<uint8_t>(state);
  return frame;
}

Result<HeartbeatMessage> decode_heartbeat(const CanFrame& frame) {
  if (const CanError e = check_data_frame(frame); e != CanError::kNone) return e;
  if (frame.id <= cob::kHeartbeat || frame.id > cob::kHeartbeat + kMaxNodeId) return CanError::kInvalidId;
  if (frame.dlc != 1) return CanError::kInvalidDlc;
  if (!valid_nmt_state(frame.data[0])) return CanError::kInvalidField;
  return HeartbeatMessage{static_cast<NodeId>(frame.id - cob::kHeartbeat), static_cast<NmtState>(frame.data[0])};
}

// ---------------------------------------------------------------------------------------------
// SDO

Result<CanFrame> encode_sdo_download_request(NodeId node, uint16_t index, uint8_t subindex, uint32_t value,
                                             uint8_t size) {
  if (!valid_node(node)) return CanError::kInvalidNode;
  if (size < 1 || size > 4 || !fits(value, size)) return CanError::kValueOutOfRange;
  return sdo_frame(cob::kSdoRx + node, expedited_cs(sdo_cs::kDownloadRequest, size), index, subindex, value);
}

Result<CanFrame> encode_sdo_upload_request(NodeId node, uint16_t index, uint8_t subindex) {
  if (!valid_node(node)) return CanError::kInvalidNode;
  return sdo_frame(cob::kSdoRx + node, sdo_cs::kUploadRequest, index, subindex, 0);
}

Result<CanFrame> encode_sdo_download_response(NodeId node, uint16_t index, uint8_t subindex) {
  if (!valid_node(node)) return CanError::kInvalidNode;
  return sdo_frame(cob::kSdoTx + node, sdo_cs::kDownloadResponse, index, subindex, 0);
}

Result<CanFrame> encode_sdo_upload_response(NodeId node, uint16_t index, uint8_t subindex, uint32_t value,
                                            uint8_t size) {
  if (!valid_node(node)) return CanError::kInvalidNode;
  if (size < 1 || size > 4 || !fits(value, size)) return CanError::kValueOutOfRange;
  return sdo_frame(cob::kSdoTx + node, expedited_cs(sdo_cs::kUploadResponse, size), index, subindex, value);
}

Result<CanFrame> encode_sdo_abort(NodeId node, uint16_t index, uint8_t subindex, uint32_t abort_code,
                                  bool from_server) {
  if (!valid_node(node)) return CanError::kInvalidNode;
  return sdo_frame((from_server ? cob::kSdoTx : cob::kSdoRx) + node, sdo_cs::kAbort, index, subindex, abort_code);
}

namespace {

// checks the frame of an SDO on the COB-ID range starting at `base` and reads what every SDO
// carries: node, multiplexer (index, subindex) and the 4 data bytes
CanError read_sdo_header(const CanFrame& frame, uint32_t base, SdoMessage& m) {
  if (const CanError e = check_data_frame(frame); e != CanError::kNone) return e;
  if (frame.id <= base || frame.id > base + kMaxNodeId) return CanError::kInvalidId;
  if (frame.dlc != 8) return CanError::kInvalidDlc;
  m.node = static_cast<NodeId>(frame.id - base);
  m.index = le::get_u16(&frame.data[1]);
  m.subindex = frame.data[3];
  m.data = le::get_u32(&frame.data[4]);
  return CanError::kNone;
}

}  // namespace

Result<SdoMessage> decode_sdo_request(const CanFrame& frame) {
  SdoMessage m;
  if (const CanError e = read_sdo_header(frame, cob::kSdoRx, m); e != CanError::kNone) return e;
  const uint8_t cs = frame.data[0];
  switch (cs >> 5) {
    case 1:  // initiate download
      m.type = SdoType::kDownloadRequest;
      if (const CanError e = decode_expedited(cs, m); e != CanError::kNone) return e;
      return m;
    case 2:  // initiate upload
      if (cs & 0x1F) return CanError::kInvalidCommand;
      m.type = SdoType::kUploadRequest;
      m.data = 0;
      return m;
    case 4:  // abort
      if (cs & 0x1F) return CanError::kInvalidCommand;
      m.type = SdoType::kAbort;
      m.abort_code = m.data;
      m.data = 0;
      return m;
    case 0:  // download segment
    case 3:  // upload segment
    case 5:  // block upload
    case 6:  // block download
      return CanError::kUnsupported;
    default:
      return CanError::kInvalidCommand;
  }
}

Result<SdoMessage> decode_sdo_response(const CanFrame& frame) {
  SdoMessage m;
  if (const CanError e = read_sdo_header(frame, cob::kSdoTx, m); e != CanError::kNone) return e;
  const uint8_t cs = frame.data[0];
  switch (cs >> 5) {
    case 3:  // initiate download response
      if (cs & 0x1F) return CanError::kInvalidCommand;
      m.type = SdoType::kDownloadResponse;
      m.data = 0;
      return m;
    case 2:  // initiate upload response
      m.type = SdoType::kUploadResponse;
      if (const CanError e = decode_expedited(cs, m); e != CanError::kNone) return e;
      return m;
    case 4:  // abort
      if (cs & 0x1F) return CanError::kInvalidCommand;
      m.type = SdoType::kAbort;
      m.abort_code = m.data;
      m.data = 0;
      return m;
    case 0:  // upload segment
    case 1:  // download segment response
    case 5:  // block download
    case 6:  // block upload
      return CanError::kUnsupported;
    default:
      return CanError::kInvalidCommand;
  }
}

// ---------------------------------------------------------------------------------------------
// PDO

Result<PdoMapping> PdoMapping::make(std::initializer_list<PdoMapEntry> entries) {
  PdoMapping mapping;
  for (const PdoMapEntry& entry : entries) {
    if (const CanError e = mapping.add(entry); e != CanError::kNone) return e;
  }
  return mapping;
}

CanError PdoMapping::add(const PdoMapEntry& entry) {
  if (entry.bits == 0 || entry.bits > kMaxBits || count_ >= kMaxEntries) return CanError::kInvalidMapping;
  if (bits_ + entry.bits > kMaxBits) return CanError::kMappingTooLong;
  entries_[count_++] = entry;
  bits_ = static_cast<uint8_t>(bits_ + entry.bits);
  return CanError::kNone;
}

unsigned PdoMapping::offset_bits(size_t i) const {
  unsigned offset = 0;
  for (size_t k = 0; k < i && k < count_; ++k) offset += entries_[k].bits;
  return offset;
}

bool operator==(const PdoMapping& a, const PdoMapping& b) {
  if (a.count_ != b.count_) return false;
  for (size_t i = 0; i < a.count_; ++i) {
    if (!(a.entries_[i] == b.entries_[i])) return false;
  }
  return true;
}

Result<CanFrame> encode_pdo(uint16_t cob_id, const PdoMapping& mapping, std::span<const uint64_t> values) {
  if (cob_id > CanFrame::kMaxStandardId) return CanError::kInvalidId;
  if (values.size() != mapping.size()) return CanError::kInvalidMapping;
  uint64_t payload = 0;
  unsigned offset = 0;
  for (size_t i = 0; i < mapping.size(); ++i) {
    const unsigned bits = mapping[i].bits;
    const uint64_t v = mapping[i].dummy() ? 0 : values[i] & mask_bits(bits);
    payload |= offset < 64 ? v << offset : 0;
    offset += bits;
  }
  CanFrame frame = make_frame(cob_id, mapping.dlc());
  for (unsigned i = 0; i < frame.dlc; ++i) frame.data[i] = static_cast<uint8_t>(payload >> (8 * i));
  return frame;
}

CanError decode_pdo(const CanFrame& frame, const PdoMapping& mapping, std::span<uint64_t> values) {
  if (const CanError e = check_data_frame(frame); e != CanError::kNone) return e;
  if (values.size() != mapping.size()) return CanError::kInvalidMapping;
  if (frame.dlc < mapping.dlc()) return CanError::kInvalidDlc;
  uint64_t payload = 0;
  for (unsigned i = 0; i < frame.dlc; ++i) payload |= static_cast<uint64_t>(frame.data[i]) << (8 * i);
  unsigned offset = 0;
  for (size_t i = 0; i < mapping.size(); ++i) {
    const unsigned bits = mapping[i].bits;
    values[i] = mapping[i].dummy() ? 0 : (payload >> offset) & mask_bits(bits);
    offset += bits;
  }
  return CanError::kNone;
}

int64_t sign_extend(uint64_t raw, unsigned bits) {
  if (bits == 0) return 0;
  if (bits >= 64) return static_cast<int64_t>(raw);
  const uint64_t v = raw & mask_bits(bits);
  const uint64_t sign = uint64_t{1} << (bits - 1);
  return static_cast<int64_t>((v ^ sign) - sign);
}

}  // namespace teleop::can
