#pragma once
// Bus-load arithmetic for classic CAN (ISO 11898-1), so a configuration can be checked before
// it runs and a master can warn above 70 %. docs/can_bus_budget.md applies it to a whole bus plan.
//
// Bits of one data frame with n data bytes, including the 3-bit intermission:
//   standard (11-bit id): 47 + 8n      (SOF 1, id 11, RTR 1, IDE 1, r0 1, DLC 4, data 8n,
//                                       CRC 15, CRC delimiter 1, ACK 2, EOF 7, IFS 3)
//   extended (29-bit id): 67 + 8n
// Stuff bits are inserted after 5 equal bits in SOF..CRC (g + 8n bits, g = 34 standard,
// 54 extended); the worst case (Davis et al., 2007) adds floor((g + 8n - 1) / 4):
//   standard: 47 + 8n + floor((33 + 8n) / 4)   -> 0 bytes: 55, 8 bytes: 135
//   extended: 67 + 8n + floor((53 + 8n) / 4)   -> 0 bytes: 80, 8 bytes: 160
// All functions are constexpr/real-time safe except the plan validation (exceptions).

#include <cstdint>
#include <span>

namespace teleop::can {

enum class CanIdFormat : uint8_t { kStandard, kExtended };

/// Load above which a configuration deserves a warning (fraction of the bitrate).
constexpr double kBusLoadWarnFraction = 0.70;

/// Bits on the wire of one classic data frame without stuff bits, intermission included.
constexpr uint32_t frame_bits_nominal(uint32_t data_bytes, CanIdFormat format = CanIdFormat::kStandard) {
  return (format == CanIdFormat::kStandard ? 47u : 67u) + 8u * data_bytes;
}
/// Bits of one classic data frame with the worst-case number of stuff bits.
constexpr uint32_t frame_bits_worst_case(uint32_t data_bytes, CanIdFormat format = CanIdFormat::kStandard) {
  const uint32_t stuffable = (format == CanIdFormat::kStandard ? 34u : 54u) + 8u * data_bytes;
  return frame_bits_nominal(data_bytes, format) + (stuffable - 1u) / 4u;
}

/// A periodic stream of identical frames: `frames` frames of `data_bytes` bytes every 1/rate_hz.
struct Traffic {
  uint32_t frames = 1;
  uint32_t data_bytes = 8;
  double rate_hz = 1.0;
  CanIdFormat format = CanIdFormat::kStandard;
};

struct BusLoad {
  double frames_per_s = 0.0;
  double bits_per_s_nominal = 0.0;
  double bits_per_s_worst_case = 0.0;
  double load_nominal = 0.0;     // fraction of the bitrate, without stuff bits
  double load_worst_case = 0.0;  // fraction of the bitrate, worst-case stuffing
  /// Worst-case load above kBusLoadWarnFraction (or the threshold given).
  bool exceeds(double fraction = kBusLoadWarnFraction) const { return load_worst_case > fraction; }
};

/// Load of the sum of several periodic streams on a bus of `bitrate_bps`.
BusLoad bus_load(std::span<const Traffic> traffic, double bitrate_bps);

}  // namespace teleop::can
