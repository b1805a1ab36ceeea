#pragma once
// Manufacturer-specific objects of the emulated drive (CiA 301 range 0x2000..0x5FFF), shared by
// a master (the hand's adapter writes them at start-up) and the emulated drive (which serves
// them): the controller gains of the cascade, and a test-only fault injection object that lets
// a test or an operator with cansend make one drive misbehave on demand.

#include <bit>
#include <cstdint>

namespace teleop::drive::drive_od {

/// Controller gains, REAL32 (IEEE 754 single) each, read/write by SDO.
constexpr uint16_t kGains = 0x2000;
namespace gain {
constexpr uint8_t kPositionKp = 1;          // [A/rad]
constexpr uint8_t kPositionKi = 2;          // [A/(rad s)]
constexpr uint8_t kPositionKd = 3;          // [A s/rad]
constexpr uint8_t kIntegralLimit = 4;       // anti-windup clamp of the integral [A]
constexpr uint8_t kMaxReferenceVelocity = 5;  // reference step limit [rad/s]
constexpr uint8_t kCurrentKp = 6;           // [V/A]
constexpr uint8_t kCurrentKi = 7;           // [V/(A s)]
constexpr uint8_t kCount = 7;
}  // namespace gain

/// Fault injection, UNSIGNED32 per subindex, write-only in effect (reads return the setting).
constexpr uint16_t kFaultInjection = 0x2F00;
namespace inject {
constexpr uint8_t kSuppressHeartbeat = 1;  // 1: stop the heartbeat, 0: resume
constexpr uint8_t kRaiseFault = 2;         // EMCY error code: raise that drive fault now
constexpr uint8_t kStall = 3;              // 1: jam the motor, 0: free it
constexpr uint8_t kDropTpdos = 4;          // drop the next N TPDOs (0xFFFFFFFF: until 0 is written)
constexpr uint8_t kRefuseSdo = 5;          // 1: abort every other SDO request (0x08000021)
constexpr uint8_t kDropRpdos = 6;          // drop the next N RPDOs
constexpr uint8_t kCount = 6;
}  // namespace inject

/// REAL32 <-> the 32 bits an expedited SDO carries.
inline uint32_t real32_bits(double value) { return std::bit_cast<uint32_t>(static_cast<float>(value)); }
inline double real32_value(uint32_t bits) { return static_cast<double>(std::bit_cast<float>(bits)); }

}  // namespace teleop::drive::drive_od
