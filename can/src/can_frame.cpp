#include "teleop/can/can_frame.h"

#include <cstring>

namespace teleop::can {

const char* to_string(CanError error) {
  switch (error) {
    case CanError::kNone:
      return "none";
    case CanError::kInvalidId:
      return "invalid id";
    case CanError::kInvalidDlc:
      return "invalid dlc";
    case CanError::kRemoteFrame:
      return "remote frame";
    case CanError::kExtendedFrame:
      return "extended frame";
    case CanError::kErrorFrame:
      return "error frame";
    case CanError::kInvalidCommand:
      return "invalid command specifier";
    case CanError::kInvalidNode:
      return "invalid node id";
    case CanError::kInvalidField:
      return "invalid field";
    case CanError::kUnsupported:
      return "unsupported";
    case CanError::kInvalidMapping:
      return "invalid mapping";
    case CanError::kMappingTooLong:
      return "mapping too long";
    case CanError::kValueOutOfRange:
      return "value out of range";
  }
  return "unknown";
}

bool CanFrame::valid() const {
  if (dlc > kMaxDlc) return false;
  if ((flags & ~(kRtr | kExtended | kError)) != 0) return false;
  // a controller error frame is its own kind: the extended and RTR bits mean nothing on it
  if (error()) return flags == kError && id <= kMaxExtendedId;
  return id <= (extended() ? kMaxExtendedId : kMaxStandardId);
}

bool operator==(const CanFrame& a, const CanFrame& b) {
  if (a.id != b.id || a.dlc != b.dlc || a.flags != b.flags) return false;
  const size_t n = a.dlc <= CanFrame::kMaxDlc ? a.dlc : CanFrame::kMaxDlc;
  return std::memcmp(a.data.data(), b.data.data(), n) == 0;
}

Result<can_frame> to_linux(const CanFrame& frame) {
  if (frame.dlc > CanFrame::kMaxDlc) return CanError::kInvalidDlc;
  if (!frame.valid())
    return frame.flags & ~(CanFrame::kRtr | CanFrame::kExtended | CanFrame::kError) ? CanError::kInvalidField
                                                                                    : CanError::kInvalidId;
  can_frame out{};
  out.can_id = frame.id;
  if (frame.extended()) out.can_id |= CAN_EFF_FLAG;
  if (frame.rtr()) out.can_id |= CAN_RTR_FLAG;
  if (frame.error()) out.can_id |= CAN_ERR_FLAG;
  out.len = frame.dlc;
  std::memcpy(out.data, frame.data.data(), frame.dlc);
  return out;
}

Result<CanFrame> from_linux(const can_frame& frame) {
  if (frame.len > CanFrame::kMaxDlc) return CanError::kInvalidDlc;
  CanFrame out;
  if (frame.can_id & CAN_ERR_FLAG) {
    out.flags |= CanFrame::kError;
    out.id = frame.can_id & CAN_ERR_MASK;
  } else if (frame.can_id & CAN_EFF_FLAG) {
    out.flags |= CanFrame::kExtended;
    out.id = frame.can_id & CAN_EFF_MASK;
  } else {
    // a standard frame must not carry bits above the 11-bit id
    if ((frame.can_id & CAN_EFF_MASK) > CAN_SFF_MASK) return CanError::kInvalidId;
    out.id = frame.can_id & CAN_SFF_MASK;
  }
  if ((frame.can_id & CAN_RTR_FLAG) && !out.error()) out.flags |= CanFrame::kRtr;
  out.dlc = frame.len;
  std::memcpy(out.data.data(), frame.data, frame.len);
  return out;
}

}  // namespace teleop::can
