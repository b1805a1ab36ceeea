#pragma once
// The CANopen master of the hand: nine CiA 402 drives (one node per SVH motor channel) on one
// CanBus, driven in cyclic synchronous position mode by SYNC (docs/can_bus_budget.md: 250 Hz,
// two motors' targets per RPDO, one 8-byte TPDO per motor).
//
// Everything runs in cycle(now), one call per bus cycle, in phases:
//   booting      NMT reset communication to each node, then wait for every node's boot-up or
//                heartbeat (timeout: kFailed, the message names the missing node)
//   configuring  expedited SDO writes, all nodes in parallel, one outstanding per node: PDO
//                communication and mapping, CSP mode, gains (0x2000), current limit, software
//                limits (0x607D), heartbeat time; an abort or a timeout is kFailed naming node,
//                object and abort code. Then NMT start.
//   enabling     SYNC every cycle; each drive walked to operation enabled (RPDO1 controlword),
//                holding its actual position as target
//   homing       (optional, SVH style) every motor driven slowly towards its hard stop until its
//                current passes a threshold; the channel's zero is set from the stop and the
//                software limits are written again
//   operational  commanded targets (clamped to the limits, counted) each cycle
//   safe hold    after any fault: quick stop to every drive, targets held; leaves by a fault
//                reset command once the causes are gone (back through enabling)
// Faults: missing heartbeat (consumer), EMCY, statusword fault, bus-off, error passive, SDO
// abort or timeout, no TPDO for `pdo_timeout_cycles`, a node that boots again. Each is latched
// per motor (HandFault bits, the same values as HAND_FAULT_* in idl/hand.idl) with the node's
// last EMCY code and SDO abort code.
//
// The adapter owns no thread and no clock: the caller paces cycle() and gives the time, so
// the same code runs in tests on a VirtualCanBus with EmulatedDrives and in the node on
// SocketCAN. Construction validates the configuration (exceptions); set_command(), cycle()
// and every accessor are real-time safe: no allocation, no blocking, no exceptions.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "teleop/can/can_bus.h"
#include "teleop/can/cia301.h"
#include "teleop/hand/hand_bus_budget.h"
#include "teleop/hand/hand_coupling.h"
#include "teleop/hand/motor_channel.h"

namespace teleop::hand {

/// Per-motor fault bits; the values of HAND_FAULT_* in idl/hand.idl.
namespace hand_fault {
constexpr uint32_t kEmcy = 1;         // the drive sent an emergency message
constexpr uint32_t kHeartbeat = 2;    // heartbeat timed out, or the node booted again
constexpr uint32_t kDrive = 4;        // statusword reports fault
constexpr uint32_t kLimit = 8;        // the last command was clamped to the software limits
constexpr uint32_t kOverCurrent = 16; // current above the limit in force
constexpr uint32_t kBusOff = 32;      // the CAN controller went bus-off
constexpr uint32_t kStalePdo = 64;    // no TPDO for pdo_timeout_cycles
constexpr uint32_t kBusPassive = 128; // the CAN controller went error passive
constexpr uint32_t kSdo = 256;        // an SDO transfer was aborted or timed out
}  // namespace hand_fault

/// Controller gains written to every drive (manufacturer object 0x2000, teleop/drive/drive_objects.h).
struct HandGains {
  double position_kp_a_per_rad = 19.8;
  double position_ki_a_per_rad_s = 150.0;
  double position_kd_a_s_per_rad = 0.32;
  double position_integral_limit_a = 0.5;     // anti-windup
  double max_reference_velocity_radps = 3.0;  // reference step limit
  double current_kp_v_per_a = 0.63;
  double current_ki_v_per_a_s = 12566.0;
};

/// SVH-style homing: each motor runs towards a hard stop until its current passes a threshold.
struct HandHomingConfig {
  bool enabled = false;
  double velocity_radps = 0.3;
  double current_threshold_a = 0.5;
  double timeout_s = 5.0;
  /// -1: towards decreasing angles, +1: increasing.
  std::array<int, kHandMotors> direction{-1, -1, -1, -1, -1, -1, -1, -1, -1};
  /// Joint angle at the hard stop [rad]: sets each channel's offset.
  HandMotorVector stop_position_rad{-0.1, -0.1, -0.1, -0.1, -0.1, -0.1, -0.1, -0.1, -0.1};
};

struct HandAdapterConfig {
  /// CANopen node id of each motor (SVH channel order).
  std::array<can::NodeId, kHandMotors> node_ids{1, 2, 3, 4, 5, 6, 7, 8, 9};
  /// Tick/radian conversion per motor (defaults match the emulated drive: 4096 ticks, 1:100).
  std::array<MotorChannelConfig, kHandMotors> channels = default_channels();
  /// Software limits of each motor [rad]: commands are clamped to them, 0x607D is set from them.
  HandMotorVector min_position_rad{0, 0, 0, 0, 0, 0, 0, 0, 0};
  HandMotorVector max_position_rad{1, 1, 1, 1, 1, 1, 1, 1, 1};
  HandGains gains;
  /// Current limit (0x6073) used when a command gives 0 [A], and the highest one accepted.
  double default_current_limit_a = 1.5;
  double max_current_limit_a = 3.0;
  /// SYNC rate: one cycle() call per period.
  double cycle_rate_hz = 250.0;
  double bitrate_bps = 1e6;
  /// Heartbeat each drive produces (0x1017) and how long the adapter waits for one.
  uint16_t heartbeat_ms = 100;
  double heartbeat_timeout_s = 0.35;
  double boot_timeout_s = 2.0;
  double sdo_timeout_s = 0.2;
  double enable_timeout_s = 1.0;
  /// A motor without TPDO for this many cycles is stale.
  uint32_t pdo_timeout_cycles = 10;
  HandHomingConfig homing;

  static std::array<MotorChannelConfig, kHandMotors> default_channels();
};

enum class HandPhase : uint8_t { kBooting, kConfiguring, kEnabling, kHoming, kOperational, kSafeHold, kFailed };
const char* to_string(HandPhase phase);

/// What the hand is told to do (motor-side angles, SVH channel order).
struct HandTargets {
  HandMotorVector position_rad{};
  /// [A]; 0 keeps the configured default.
  HandMotorVector current_limit_a{};
  /// false: quick stop and hold; true: follow the targets.
  bool enable = false;
  /// Rising edge: try to leave safe hold (clears the faults whose cause is gone).
  bool fault_reset = false;
};

/// The last feedback and fault state of every motor.
struct HandFeedback {
  HandMotorVector position_rad{};
  HandMotorVector velocity_radps{};
  HandMotorVector current_a{};
  /// The targets sent in the last cycle [rad].
  HandMotorVector target_rad{};
  std::array<uint16_t, kHandMotors> statusword{};
  /// Last EMCY error code (0 = none) and last SDO abort code (0 = none) of each drive.
  std::array<uint16_t, kHandMotors> error_code{};
  std::array<uint32_t, kHandMotors> sdo_abort_code{};
  /// hand_fault bits: latched ones plus the momentary kLimit / kOverCurrent.
  std::array<uint32_t, kHandMotors> faults{};
};

struct HandAdapterStats {
  uint64_t cycles = 0;
  uint64_t syncs_sent = 0;
  uint64_t rpdos_sent = 0;
  uint64_t tpdos_received = 0;
  uint64_t send_failures = 0;
  uint64_t emcys = 0;
  uint64_t sdo_writes = 0;
  uint64_t sdo_aborts = 0;
  uint64_t unexpected_frames = 0;  // SDO responses nobody waits for, unknown nodes, bad payloads
  uint64_t clamped_commands = 0;   // commands with a target or current limit out of range
  uint64_t rejected_commands = 0;  // commands with NaN/Inf (kept the previous targets)
  uint64_t safe_holds = 0;         // entries into safe hold
  uint64_t fault_resets = 0;
};

class HandAdapter {
 public:
  /// Throws std::invalid_argument for an invalid configuration (duplicate or invalid node ids,
  /// limits, rates, timeouts, gains).
  HandAdapter(can::CanBus& bus, const HandAdapterConfig& config);

  /// Sets the targets (clamped to the limits and counted; NaN/Inf rejected and counted).
  void set_command(const HandTargets& targets);
  /// One bus cycle at monotonic time now_ns: reads every waiting frame, advances the phase,
  /// sends SYNC and the targets. Call at cycle_rate_hz.
  void cycle(int64_t now_ns);

  HandPhase phase() const { return phase_; }
  /// True once the hand reached operational the first time (boot, configuration, homing done).
  bool started() const { return started_; }
  const HandFeedback& feedback() const { return feedback_; }
  const HandAdapterStats& stats() const { return stats_; }
  /// The 20 joint angles of the last feedback, q = S_m m + q0.
  HandJointVector joint_positions() const { return coupling_.joints_from_motors(feedback_.position_rad); }
  /// The 20 joint velocities, dq = S_m dm.
  HandJointVector joint_velocities() const;
  /// Why the adapter failed (kFailed) or what put it in safe hold; empty otherwise.
  const char* message() const { return message_.data(); }
  /// Frames of every motor's channel (after homing: with the offset found).
  const MotorChannel& channel(size_t motor) const { return drives_[motor].channel; }
  const HandAdapterConfig& config() const { return config_; }
  const HandBusBudget& bus_budget() const { return budget_; }

 private:
  struct SdoWrite {
    uint16_t index = 0;
    uint8_t subindex = 0;
    uint8_t size = 0;
    uint32_t value = 0;
  };
  struct Drive {
    explicit Drive(const MotorChannelConfig& c) : channel(c) {}
    MotorChannel channel;
    can::NodeId node = 0;
    // NMT and heartbeat consumer
    bool seen = false;
    int64_t last_heartbeat_ns = 0;
    // feedback
    bool have_feedback = false;
    uint64_t last_tpdo_cycle = 0;
    int32_t position_ticks = 0;
    // SDO client: a ring of writes, one outstanding
    std::array<SdoWrite, 64> sdo{};
    size_t sdo_head = 0;
    size_t sdo_count = 0;
    bool sdo_busy = false;
    uint8_t sdo_attempts = 0;  // sends of the write at the head
    int64_t sdo_sent_ns = 0;
    // control
    uint16_t controlword = 0;
    uint16_t sent_controlword = 0xFFFF;
    int32_t target_ticks = 0;
    double hold_rad = 0.0;
    double current_limit_a = 0.0;
    uint32_t latched = 0;
    // homing
    bool homed = false;
  };

  // --- hand_adapter.cpp ---
  void validate() const;
  // phases
  void boot(int64_t now_ns);
  void configure(int64_t now_ns);
  void enable(int64_t now_ns);
  void home(int64_t now_ns);
  void operate();
  void hold();
  void check_faults(int64_t now_ns);
  void enter(HandPhase phase, int64_t now_ns);
  void enter_safe_hold(int64_t now_ns);
  void fail(const char* format, ...) __attribute__((format(printf, 2, 3)));
  void update_feedback_faults();
  void hold_actual_positions();
  // --- hand_adapter_bus.cpp ---
  // the SDO client
  void queue_configuration(Drive& d, size_t motor);
  void queue_limits(Drive& d, size_t motor);
  void queue_sdo(Drive& d, uint16_t index, uint8_t subindex, uint32_t value, uint8_t size);
  bool pump_sdo(int64_t now_ns);
  // receive
  void receive_all(int64_t now_ns);
  void handle_frame(const can::CanFrame& frame, int64_t now_ns);
  void handle_tpdo(Drive& d, size_t motor, const can::CanFrame& frame);
  void handle_sdo_response(Drive& d, size_t motor, const can::CanFrame& frame);
  // send
  void send(const can::Result<can::CanFrame>& frame);
  void send_cyclic();

  can::CanBus& bus_;
  HandAdapterConfig config_;
  HandCoupling coupling_;
  HandBusBudget budget_;
  std::vector<Drive> drives_;  // sized at construction, never resized
  std::array<int8_t, can::kMaxNodeId + 1> motor_of_node_{};
  HandPhase phase_ = HandPhase::kBooting;
  bool started_ = false;
  bool boot_sent_ = false;
  int64_t phase_start_ns_ = 0;
  int64_t last_now_ns_ = 0;
  double period_s_ = 0.004;
  HandTargets command_;
  bool commanded_ = false;
  bool last_fault_reset_ = false;
  HandFeedback feedback_;
  HandAdapterStats stats_;
  std::array<char, 256> message_{};
};

/// Validates the configuration's bus load: a warning when the worst case exceeds 70 %
/// (kBusLoadWarnFraction), nullopt otherwise.
std::optional<std::string> bus_load_warning(const HandAdapterConfig& config);
/// The HandBusPlan of a configuration (rate, bitrate, heartbeat).
HandBusPlan hand_bus_plan(const HandAdapterConfig& config);

}  // namespace teleop::hand
