#pragma once
// A classic CAN 2.0 frame as the stack sees it, the error type every decoder returns, and the
// conversion to and from SocketCAN's struct can_frame (<linux/can.h>). Plain data, fixed size:
// everything here is real-time safe (no heap, no exceptions).

#include <linux/can.h>

#include <array>
#include <cassert>
#include <cstddef>
#include <cstdint>

namespace teleop::can {

/// Why a frame could not be encoded or decoded. kNone means success.
enum class [[nodiscard]] CanError : uint8_t{
    kNone = 0,
    kInvalidId,        // id outside the 11/29-bit range, or not the COB-ID of the service
    kInvalidDlc,       // dlc above 8, or not the length the service requires
    kRemoteFrame,      // RTR frame where the service carries data
    kExtendedFrame,    // 29-bit id where CANopen uses 11-bit ids
    kErrorFrame,       // controller error frame where a data frame was expected
    kInvalidCommand,   // unknown command specifier (NMT, SDO)
    kInvalidNode,      // node id outside 1..127 (0 is only valid as NMT broadcast)
    kInvalidField,     // another field out of range (SYNC counter, NMT state, reserved bits)
    kUnsupported,      // valid protocol this stack does not implement (segmented/block SDO)
    kInvalidMapping,   // PDO mapping entry of length 0 or too many entries
    kMappingTooLong,   // PDO mapping longer than 64 bits
    kValueOutOfRange,  // a value does not fit its field (or is NaN)
};

/// Short lowercase name of the error, for logs.
const char* to_string(CanError error);

/// A value or the reason there is none. Real-time safe; T must be default-constructible.
template <typename T>
class [[nodiscard]] Result {
 public:
  Result(const T& value) : value_(value) {}  // NOLINT(google-explicit-constructor): return value;
  Result(CanError error) : error_(error) { assert(error != CanError::kNone); }  // NOLINT: return error;

  bool ok() const { return error_ == CanError::kNone; }
  explicit operator bool() const { return ok(); }
  CanError error() const { return error_; }
  /// The value; only meaningful when ok().
  const T& value() const {
    assert(ok());
    return value_;
  }
  const T& operator*() const { return value(); }
  const T* operator->() const { return &value(); }

 private:
  T value_{};
  CanError error_ = CanError::kNone;
};

/// One classic CAN frame (at most 8 data bytes). `id` holds the bare identifier (11 or 29 bits,
/// or the error class bits of an error frame); RTR, extended format and error are in `flags`.
struct CanFrame {
  static constexpr uint8_t kRtr = 0x01;       // remote transmission request
  static constexpr uint8_t kExtended = 0x02;  // 29-bit identifier
  static constexpr uint8_t kError = 0x04;     // controller error frame (SocketCAN CAN_ERR_FLAG)
  static constexpr uint32_t kMaxStandardId = 0x7FF;
  static constexpr uint32_t kMaxExtendedId = 0x1FFFFFFF;
  static constexpr uint8_t kMaxDlc = 8;

  uint32_t id = 0;
  uint8_t dlc = 0;
  uint8_t flags = 0;
  std::array<uint8_t, 8> data{};

  bool rtr() const { return (flags & kRtr) != 0; }
  bool extended() const { return (flags & kExtended) != 0; }
  bool error() const { return (flags & kError) != 0; }
  /// Id within its format's range, dlc at most 8, no unknown flag bits.
  bool valid() const;

  /// Equal id, dlc, flags and the first dlc data bytes (bytes beyond dlc do not matter).
  friend bool operator==(const CanFrame& a, const CanFrame& b);
};

/// The SocketCAN form of a frame: can_id with CAN_EFF/RTR/ERR flags, len, data.
/// Fails (kInvalidId / kInvalidDlc / kInvalidField) for a frame that is not valid().
Result<can_frame> to_linux(const CanFrame& frame);
/// The stack's form of a SocketCAN frame; fails for len above 8 or an id outside its range.
Result<CanFrame> from_linux(const can_frame& frame);

// the struct we convert to is the classic one: 16 bytes, data 8-aligned at offset 8
static_assert(sizeof(can_frame) == 16, "unexpected struct can_frame layout");
static_assert(offsetof(can_frame, data) == 8, "unexpected struct can_frame layout");

/// Little-endian field access (CANopen is little-endian on the wire). No bounds checks: the
/// callers have checked the dlc.
namespace le {
inline void put_u16(uint8_t* p, uint16_t v) {
  p[0] = static_cast<uint8_t>(v);
  p[1] = static_cast<uint8_t>(v >> 8);
}
inline void put_u32(uint8_t* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<uint8_t>(v >> (8 * i));
}
inline uint16_t get_u16(const uint8_t* p) { return static_cast<uint16_t>(p[0] | (p[1] << 8)); }
inline uint32_t get_u32(const uint8_t* p) {
  return static_cast<uint32_t>(p[0]) | (static_cast<uint32_t>(p[1]) << 8) | (static_cast<uint32_t>(p[2]) << 16) |
         (static_cast<uint32_t>(p[3]) << 24);
}
}  // namespace le

}  // namespace teleop::can
