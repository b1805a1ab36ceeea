#pragma once
// One emulated CANopen servo drive (the hand's motor controllers, an arm's joint drives),
// speaking CiA 301 / CiA 402 on a CanBus endpoint, for tests and the HIL emulators:
//   - NMT slave: boot-up message, initialising -> pre-operational -> operational / stopped,
//     reset node / reset communication; heartbeat producer (0x1017) and consumer (0x1016, two
//     entries: its master's heartbeat lost -> EMCY 0x8130 and the reaction 0x6007 selects)
//   - SDO server, expedited transfers, with abort codes for every refused access
//   - CiA 402 state machine driven by the controlword (RPDO or SDO), statusword, EMCY on faults
//   - cyclic synchronous position (0x6060 = 8) and torque (10) modes: RPDO targets latched at
//     SYNC, TPDOs (position actual, current actual, statusword by default) sampled at SYNC; RPDO
//     and TPDO mappings configurable over SDO, including dummy entries (several nodes sharing
//     one RPDO)
//   - inside: cascaded position PID (anti-windup, reference step limit) -> current PI
//     (anti-windup) -> PWM -> a DC motor with gearbox turning its plant (DrivePlant): by
//     default its own finger link between hard stops, or a channel of a shared simulation such
//     as the MuJoCo hand (drive::DriveGroup keeps such drives and their plant in lock-step)
//   - fault injection: silence the heartbeat, raise a fault with an EMCY code, jam the motor,
//     drop or delay PDOs
//
// No threads and no clocks inside: the owner calls step(dt), which reads the frames waiting on
// the bus, advances the drive by dt and sends what the drive would have sent. Deterministic;
// real-time safe (no allocation, no exceptions) after construction.
//
// Object dictionary (all subindex 0 unless noted):
//   0x1000 device type (ro), 0x1001 error register (ro), 0x1016 consumer heartbeat sub 1..2
//   ((node << 16) | ms, rw), 0x1017 heartbeat ms (rw),
//   0x1018 identity sub 1..4 (ro), 0x1400/0x1401 RPDO communication (sub 1 COB-ID, 2 type),
//   0x1600/0x1601 RPDO mapping, 0x1800/0x1801 TPDO communication (sub 1, 2, 3 inhibit,
//   5 event timer ms), 0x1A00/0x1A01 TPDO mapping, the CiA 402 objects of cia402::od, and the
//   manufacturer objects of drive_objects.h (0x2000 gains, 0x2F00 fault injection).
// Defaults: RPDO1 0x200+id [0x6040, 0x607A] synchronous; TPDO1 0x180+id [0x6064, 0x6078,
// 0x6041] on every SYNC; RPDO2 / TPDO2 disabled (TPDO2 mapped [0x606C, 0x603F]).
// Modes of operation start at 0 (no mode: the drive holds its position when enabled); the
// master sets 8 or 10. In CSP the master should send the actual position as target before
// enabling: the drive starts from the actual position and ramps towards the target at the
// reference limit. In CST the target torque 0x6071 is the motor's, per mille of the rated torque
// 0x6076 (k_t * rated current, mN m): the current loop drives target / k_t within 0x6073 (bit 11
// "internal limit" when clamped); what reaches the plant is that torque times gear ratio and
// efficiency.
// Quick stop brakes with the position loop and holds (quick stop option code 6, 0x605A, which
// takes no other value): enable
// operation resumes (transition 16), disable voltage leaves (12). Following error: the link
// farther than 0x6065 from the reference for 0x6066 ms (CSP) -> fault, EMCY 0x8611. A lost
// master (a consumed heartbeat silent longer than its time; the watch starts with its first
// heartbeat) acts through 0x6007 (default from the config: 0, no action; 1 fault, 2 disable
// voltage, 3 quick stop), and the controlword it last wrote is no longer obeyed until it writes
// one again. The NMT state itself does not act on the CiA 402 state; a reset keeps the link where
// it is (an absolute encoder). Torque actual (0x6077) is k_t * current per mille of 0x6076.
//
// Inside (drive/src/), one part per responsibility, composed here: the object dictionary
// (one table), the SDO server, the PDO engine, the NMT slave, the CiA 402 device side, the
// servo controller, the motor model (winding, gearbox, encoder), the own link plant, the
// heartbeat consumer and fault injection.

#include <array>
#include <cstdint>
#include <memory>

#include "teleop/can/can_bus.h"
#include "teleop/can/cia301.h"
#include "teleop/can/cia402.h"
#include "teleop/drive/drive_plant.h"

namespace teleop::drive {

/// DC motor and gearbox; the finger link (output side, with hard stops) is the drive's own plant
/// when it is given none (rotor inertia and viscous friction then act at its output too).
struct EmulatedMotorParams {
  double supply_v = 24.0;
  double resistance_ohm = 4.0;
  double inductance_h = 2e-4;
  double torque_constant_nm_per_a = 0.01;  // also the back-EMF constant [V s/rad]
  double rotor_inertia_kgm2 = 1e-7;
  double gear_ratio = 100.0;  // motor revolutions per output revolution
  double gear_efficiency = 0.8;
  double link_inertia_kgm2 = 1e-4;    // output side
  double viscous_nms_per_rad = 0.01;  // output side
  double stop_min_rad = -0.1;         // hard stops of the link (output side)
  double stop_max_rad = 1.2;
  double stop_stiffness_nm_per_rad = 200.0;
  double stop_damping_nms_per_rad = 0.5;
  double encoder_ticks_per_rev = 4096.0;  // motor side, after quadrature
  /// A holding brake, engaged whenever the power stage is off (as an arm joint has, which would
  /// fall without it): the plant is told it is jammed then.
  bool holding_brake = false;
};

/// The cascade inside the drive. Position loop gains act on the output angle [rad] and give a
/// current reference [A]; current loop gains give a voltage [V].
struct EmulatedControllerParams {
  double substep_s = 50e-6;             // current loop and plant period (20 kHz)
  unsigned position_loop_divider = 10;  // position loop every 10 substeps (2 kHz)
  // PD part placed for a critically damped ~120 rad/s loop on the default link (J = 1.1e-3
  // kg m^2 at the output, 0.8 Nm/A): kp = J w^2 / Kt, kd = (2 J w - b) / Kt
  double position_kp_a_per_rad = 19.8;
  double position_ki_a_per_rad_s = 150.0;
  double position_kd_a_s_per_rad = 0.32;
  double position_integral_limit_a = 0.5;
  double max_reference_velocity_radps = 3.0;  // reference step limit = this * position period
  double velocity_filter_hz = 200.0;
  double current_kp_v_per_a = 0.63;       // ~ L * 2 pi 500 Hz
  double current_ki_v_per_a_s = 12566.0;  // ~ R * 2 pi 500 Hz
};

struct EmulatedDriveConfig {
  can::NodeId node_id = 1;
  uint16_t heartbeat_ms = 100;
  uint32_t vendor_id = 0x00000ACE;
  uint32_t product_code = 0x00005748;
  uint32_t revision = 0x00010000;
  uint32_t serial = 1;
  EmulatedMotorParams motor;
  EmulatedControllerParams control;
  double initial_position_rad = 0.0;          // of the own link; the encoder reads 0 at 0 rad
  double rated_current_a = 1.0;               // 0x6075, unit of 0x6073 / 0x6078
  double max_current_a = 1.5;                 // default of 0x6073
  double peak_current_a = 3.0;                // hardware limit: 0x6073 cannot exceed it
  double following_error_window_rad = 0.2;    // default of 0x6065
  uint16_t following_error_timeout_ms = 100;  // default of 0x6066
  double fault_reaction_time_s = 0.002;       // fault reaction active -> fault
  int16_t abort_connection_option = 0;        // default of 0x6007 (can::cia402::abort_connection)
};

struct EmulatedDriveStats {
  uint64_t frames_received = 0;
  uint64_t frames_sent = 0;
  uint64_t send_failures = 0;
  uint64_t malformed_frames = 0;
  uint64_t syncs = 0;
  uint64_t sdo_requests = 0;
  uint64_t sdo_aborts_sent = 0;
  uint64_t rpdos_received = 0;
  uint64_t rpdos_dropped = 0;  // by fault injection
  uint64_t tpdos_sent = 0;
  uint64_t tpdos_dropped = 0;  // by fault injection or a full delay queue
  uint64_t emcys_sent = 0;
  uint64_t heartbeats_sent = 0;
  uint64_t heartbeat_timeouts = 0;  // of a node the drive consumes (0x1016): its master lost
};

class EmulatedDrive {
 public:
  static constexpr uint32_t kDeviceType = 0x00020192;  // CiA 402 servo drive
  static constexpr uint32_t kDropForever = 0xFFFFFFFF;

  /// Does not send anything yet: the boot-up message goes out on the first step().
  /// Throws std::invalid_argument for an invalid node id or non-physical parameters.
  /// The motor turns the drive's own link (config.motor's link and stops).
  EmulatedDrive(can::CanBus& bus, const EmulatedDriveConfig& config);
  /// The motor turns `plant` (which must outlive the drive); the encoder reads its angle.
  EmulatedDrive(can::CanBus& bus, const EmulatedDriveConfig& config, DrivePlant& plant);
  ~EmulatedDrive();
  EmulatedDrive(const EmulatedDrive&) = delete;
  EmulatedDrive& operator=(const EmulatedDrive&) = delete;

  /// Processes the frames waiting on the bus at the current time, then advances the drive by
  /// dt_s (in substeps of control.substep_s; a remainder carries over to the next call).
  void step(double dt_s);

  // --- observation (for tests and the emulator's own report) ---
  can::NodeId node_id() const { return config_.node_id; }
  /// The configuration, with the gains as last written over SDO (object 0x2000).
  const EmulatedDriveConfig& config() const { return config_; }
  can::NmtState nmt_state() const;
  bool booted() const;
  can::cia402::State state() const;
  uint16_t statusword() const;
  uint16_t controlword() const;
  int8_t mode_of_operation() const;
  uint16_t error_code() const;
  /// 0x6071 [per mille of rated torque], 0x6076 [N m] (motor side), 0x6007.
  int16_t target_torque_permille() const;
  double rated_torque_nm() const;
  int16_t abort_connection_option() const;
  double time_s() const { return static_cast<double>(now_ns_) * 1e-9; }
  /// True plant angle [rad] (output side) and velocity, true motor current.
  double position_rad() const;
  double velocity_radps() const;
  double current_a() const;
  /// Position-loop reference after software limits and the step limit [rad].
  double reference_rad() const;
  int32_t position_ticks() const;
  int32_t target_ticks() const;
  /// Software position limits (0x607D sub 1, 2) [ticks].
  int32_t limit_min_ticks() const;
  int32_t limit_max_ticks() const;
  /// Encoder ticks per output radian (ticks_per_rev * gear_ratio / 2 pi).
  double ticks_per_rad() const;
  /// Current limit in force [A] (0x6073 and the hardware peak).
  double current_limit_a() const;
  const EmulatedDriveStats& stats() const;

  // --- fault injection ---
  /// Stops (true) or resumes the heartbeat; everything else keeps working.
  void set_heartbeat_suppressed(bool suppressed);
  /// A drive fault with this EMCY code (and vendor bytes): EMCY now, fault reaction, fault.
  void raise_fault(uint16_t error_code, const std::array<uint8_t, 5>& vendor = {});
  /// Jams the motor mechanically (true) or frees it; a position demand it cannot follow then
  /// ends in a following error (EMCY 0x8611) after 0x6066 ms.
  void set_stalled(bool stalled);
  /// Drops the next `count` TPDOs / RPDOs (kDropForever: until called again with 0).
  void drop_tpdos(uint32_t count);
  void drop_rpdos(uint32_t count);
  /// Aborts every SDO request (code 0x08000021, local control) except to the fault injection
  /// object 0x2F00, e.g. to test a master's reaction to SDO aborts.
  void set_sdo_refused(bool refused);
  /// Sends every TPDO this much later than sampled (0 = at once); at most 16 wait at a time.
  void set_tpdo_delay(double seconds);

 private:
  struct Parts;  // drive/src/drive_parts.h

  EmulatedDrive(can::CanBus& bus, const EmulatedDriveConfig& config, DrivePlant* plant);

  void handle_frame(const can::CanFrame& frame);
  void handle_nmt(const can::NmtMessage& message);
  void reset_application();
  void reset_communication();
  void substep();

  EmulatedDriveConfig config_;  // the parts read it; SDO writes its gains
  int64_t now_ns_ = 0;
  int64_t pending_ns_ = 0;  // time stepped but not yet simulated (less than a substep)
  int64_t substep_ns_ = 50000;
  unsigned substep_count_ = 0;
  // the parts, allocated once at construction: they keep references to each other and to
  // config_ and now_ns_, so they live at a fixed address
  std::unique_ptr<Parts> parts_;
};

}  // namespace teleop::drive
