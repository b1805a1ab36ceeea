// EmulatedDrive: the composition of its parts (drive_parts.h) and the order things happen in
// one step: frames in, boot-up, the controlword, the physics in substeps, then the timers.
#include "teleop/drive/emulated_drive.h"

#include <algorithm>
#include <cmath>

#include "drive_config.h"
#include "drive_parts.h"

namespace teleop::drive {

using can::CanFrame;
using can::NmtCommand;
using can::NmtState;

EmulatedDrive::EmulatedDrive(can::CanBus& bus, const EmulatedDriveConfig& config)
    : EmulatedDrive(bus, config, nullptr) {}

EmulatedDrive::EmulatedDrive(can::CanBus& bus, const EmulatedDriveConfig& config, DrivePlant& plant)
    : EmulatedDrive(bus, config, &plant) {}

EmulatedDrive::EmulatedDrive(can::CanBus& bus, const EmulatedDriveConfig& config, DrivePlant* plant) : config_(config) {
  drive::validate(config);
  substep_ns_ = std::max<int64_t>(1, std::llround(config.control.substep_s * 1e9));
  parts_ = std::make_unique<Parts>(bus, config_, now_ns_, plant);
  reset_application();
  reset_communication();
}

EmulatedDrive::~EmulatedDrive() = default;

// NMT reset node: the application objects and the CiA 402 state start again; the link stays
// where it is (an absolute encoder), the controller holds it there
void EmulatedDrive::reset_application() {
  parts_->device.reset();
  parts_->servo.reset(parts_->motor.measured_rad());
}

void EmulatedDrive::reset_communication() {
  parts_->nmt.reset_communication();
  parts_->pdos.reset(config_.node_id);
  parts_->heartbeats.reset();
  parts_->faults.clear_delayed();
}

void EmulatedDrive::step(double dt_s) {
  if (!(dt_s >= 0) || !std::isfinite(dt_s)) return;
  Parts& p = *parts_;

  // the frames on the bus at the current time
  CanFrame frame;
  while (p.link.receive(frame)) handle_frame(frame);

  // initialisation ends with the boot-up message (after power-on and after every reset)
  if (p.nmt.initialising()) {
    p.nmt.boot(now_ns_);
    p.device.initialised();
  }

  // the controlword is level-triggered (only fault reset needs an edge, seen on write)
  p.device.evaluate_held_controlword();

  // physics and control
  pending_ns_ += std::llround(dt_s * 1e9);
  while (pending_ns_ >= substep_ns_) {
    substep();
    pending_ns_ -= substep_ns_;
  }
  now_ns_ += std::llround(dt_s * 1e9);

  // what is due at the new time
  p.nmt.produce_heartbeat(now_ns_, p.faults.heartbeat_suppressed());
  if (p.heartbeats.timed_out(now_ns_)) {
    ++p.link.stats().heartbeat_timeouts;
    p.device.connection_lost();
  }
  p.pdos.service_event_timers(p.objects, now_ns_);
  p.faults.release_delayed(now_ns_);
}

void EmulatedDrive::handle_frame(const CanFrame& frame) {
  Parts& p = *parts_;
  ++p.link.stats().frames_received;
  if (frame.error()) return;         // the controller's own business
  if (p.nmt.initialising()) return;  // a node in initialisation takes part in nothing
  if (p.pdos.receive(frame, p.objects)) return;
  if (frame.extended()) return;  // every fixed CANopen service has an 11-bit id
  const can::NodeId id = config_.node_id;
  if (frame.id == can::cob::kNmt) {
    const auto nmt = can::decode_nmt(frame);
    if (!nmt.ok()) {
      ++p.link.stats().malformed_frames;
      return;
    }
    if (nmt->node == 0 || nmt->node == id) handle_nmt(*nmt);
    return;
  }
  if (frame.id == can::cob::kSync) {
    if (can::decode_sync(frame).ok()) {
      p.pdos.sync(p.objects, now_ns_);
    } else {
      ++p.link.stats().malformed_frames;
    }
    return;
  }
  if (frame.id == static_cast<uint32_t>(can::cob::kSdoRx + id)) p.sdo.handle(frame, p.objects);
  // the heartbeats of the nodes it consumes (its master's)
  if (const auto heartbeat = can::decode_heartbeat(frame); heartbeat.ok()) p.heartbeats.heard(heartbeat->node, now_ns_);
}

void EmulatedDrive::handle_nmt(const can::NmtMessage& message) {
  Parts& p = *parts_;
  switch (message.command) {
    case NmtCommand::kStart:
      if (!p.nmt.operational()) {
        p.nmt.set_state(NmtState::kOperational);
        p.pdos.start(now_ns_);
      }
      break;
    case NmtCommand::kStop:
      p.nmt.set_state(NmtState::kStopped);
      break;
    case NmtCommand::kEnterPreOperational:
      p.nmt.set_state(NmtState::kPreOperational);
      break;
    case NmtCommand::kResetNode:
      reset_application();
      reset_communication();
      p.nmt.restart();
      break;
    case NmtCommand::kResetCommunication:
      reset_communication();
      p.nmt.restart();
      break;
  }
  if (!p.nmt.operational()) p.pdos.forget_pending();
}

// one current-loop period; the position loop runs every position_loop_divider-th of them
void EmulatedDrive::substep() {
  Parts& p = *parts_;
  const unsigned divider = config_.control.position_loop_divider;
  if (substep_count_ % divider == 0) p.device.control_position(substep_ns_ * divider);
  ++substep_count_;
  if (p.device.power_on()) {
    p.motor.energise(p.servo.current_loop(p.motor.current_a()));
  } else {
    p.motor.switch_off();
  }
  // jammed: stalled by fault injection, or held by the brake while the power is off
  p.motor.turn(p.faults.stalled() || (config_.motor.holding_brake && !p.device.power_on()));
  p.device.advance_fault_reaction(substep_ns_);
}

// --- observation -----------------------------------------------------------------------------

can::NmtState EmulatedDrive::nmt_state() const { return parts_->nmt.state(); }
bool EmulatedDrive::booted() const { return !parts_->nmt.initialising(); }
can::cia402::State EmulatedDrive::state() const { return parts_->device.state(); }
uint16_t EmulatedDrive::statusword() const { return parts_->device.statusword(); }
uint16_t EmulatedDrive::controlword() const { return parts_->device.controlword(); }
int8_t EmulatedDrive::mode_of_operation() const { return parts_->device.mode(); }
uint16_t EmulatedDrive::error_code() const { return parts_->device.error_code(); }
int16_t EmulatedDrive::target_torque_permille() const { return parts_->device.target_torque_permille(); }
double EmulatedDrive::rated_torque_nm() const { return parts_->device.rated_torque_mnm() * 1e-3; }
int16_t EmulatedDrive::abort_connection_option() const { return parts_->device.abort_connection_option(); }
double EmulatedDrive::position_rad() const { return parts_->motor.position_rad(); }
double EmulatedDrive::velocity_radps() const { return parts_->motor.velocity_radps(); }
double EmulatedDrive::current_a() const { return parts_->motor.current_a(); }
double EmulatedDrive::reference_rad() const { return parts_->servo.reference_rad(); }
int32_t EmulatedDrive::position_ticks() const { return parts_->motor.encoder_ticks(); }
int32_t EmulatedDrive::target_ticks() const { return parts_->device.target_ticks(); }
int32_t EmulatedDrive::limit_min_ticks() const { return parts_->device.limit_min_ticks(); }
int32_t EmulatedDrive::limit_max_ticks() const { return parts_->device.limit_max_ticks(); }
double EmulatedDrive::ticks_per_rad() const { return parts_->motor.ticks_per_rad(); }
double EmulatedDrive::current_limit_a() const { return parts_->device.current_limit_a(); }
const EmulatedDriveStats& EmulatedDrive::stats() const { return parts_->link.stats(); }

// --- fault injection -------------------------------------------------------------------------

void EmulatedDrive::set_heartbeat_suppressed(bool suppressed) { parts_->faults.set_heartbeat_suppressed(suppressed); }
void EmulatedDrive::raise_fault(uint16_t error_code, const std::array<uint8_t, 5>& vendor) {
  parts_->device.raise_fault(error_code, vendor);
}
void EmulatedDrive::set_stalled(bool stalled) { parts_->faults.set_stalled(stalled); }
void EmulatedDrive::drop_tpdos(uint32_t count) { parts_->faults.drop_tpdos(count); }
void EmulatedDrive::drop_rpdos(uint32_t count) { parts_->faults.drop_rpdos(count); }
void EmulatedDrive::set_sdo_refused(bool refused) { parts_->faults.set_sdo_refused(refused); }
void EmulatedDrive::set_tpdo_delay(double seconds) { parts_->faults.set_tpdo_delay(seconds); }

}  // namespace teleop::drive
