#pragma once
// Test rig: one EmulatedDrive and a test "master" on a VirtualCanBus, with the master-side
// helpers the tests need (SDO round trips, a CSP cycle, bring-up to operation enabled).

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "teleop/can/cia301.h"
#include "teleop/can/cia402.h"
#include "teleop/can/virtual_can_bus.h"
#include "teleop/drive/emulated_drive.h"

namespace teleop::drive::test {

using namespace can;  // the CANopen core the drive is built on
namespace od = cia402::od;
using cia402::State;

/// What the default TPDO1 carries: position actual, current actual, statusword.
struct Feedback {
  int32_t position_ticks = 0;
  int16_t current_permille = 0;
  uint16_t statusword = 0;
};

inline const PdoMapping& default_rpdo1() {
  static const PdoMapping m = *PdoMapping::make({{0x6040, 0, 16}, {0x607A, 0, 32}});
  return m;
}
inline const PdoMapping& default_tpdo1() {
  static const PdoMapping m = *PdoMapping::make({{0x6064, 0, 32}, {0x6078, 0, 16}, {0x6041, 0, 16}});
  return m;
}

inline std::optional<Feedback> decode_feedback(const CanFrame& frame) {
  uint64_t v[3];
  if (decode_pdo(frame, default_tpdo1(), v) != CanError::kNone) return std::nullopt;
  return Feedback{static_cast<int32_t>(sign_extend(v[0], 32)), static_cast<int16_t>(sign_extend(v[1], 16)),
                  static_cast<uint16_t>(v[2])};
}

class DriveRig {
 public:
  explicit DriveRig(const EmulatedDriveConfig& config = {})
      : master_(bus_.open("master")),
        drive_ep_(bus_.open("drive")),
        drive_(std::make_unique<EmulatedDrive>(*drive_ep_, config)) {}
  /// The drive turns `plant` (which must outlive the rig).
  DriveRig(const EmulatedDriveConfig& config, DrivePlant& plant)
      : master_(bus_.open("master")),
        drive_ep_(bus_.open("drive")),
        drive_(std::make_unique<EmulatedDrive>(*drive_ep_, config, plant)) {}

  VirtualCanBus& bus() { return bus_; }
  VirtualCanEndpoint& master() { return *master_; }
  EmulatedDrive& drive() { return *drive_; }
  const EmulatedDrive& drive() const { return *drive_; }
  NodeId node() const { return drive_->node_id(); }
  /// Every frame the master has received, in bus order.
  const std::vector<CanFrame>& received() const { return received_; }
  void clear_received() { received_.clear(); }

  /// Steps the drive by dt (in steps of at most 1 ms) and collects what it sent.
  void run(double dt_s, double step_s = 1e-3) {
    while (dt_s > 1e-12) {
      const double h = dt_s < step_s ? dt_s : step_s;
      drive_->step(h);
      drain();
      dt_s -= h;
    }
  }
  void drain() {
    CanFrame f;
    while (master_->receive(f, std::chrono::nanoseconds::zero()) == CanStatus::kOk) received_.push_back(f);
  }

  void send(const Result<CanFrame>& frame) {
    ASSERT_TRUE(frame.ok()) << to_string(frame.error());
    ASSERT_EQ(master_->send(*frame), CanStatus::kOk);
  }
  void send_frame(const CanFrame& frame) { ASSERT_EQ(master_->send(frame), CanStatus::kOk); }

  /// Frames received with this id.
  std::vector<CanFrame> frames(uint32_t id) const {
    std::vector<CanFrame> out;
    for (const CanFrame& f : received_) {
      if (f.id == id) out.push_back(f);
    }
    return out;
  }

  /// Sends an SDO request, steps the drive 1 ms, returns its response (or kInvalidId if none).
  Result<SdoMessage> sdo(const Result<CanFrame>& request) {
    clear_received();
    send(request);
    run(1e-3);
    for (const CanFrame& f : received_) {
      if (f.id == static_cast<uint32_t>(cob::kSdoTx + node())) return decode_sdo_response(f);
    }
    return CanError::kInvalidId;
  }
  Result<SdoMessage> sdo_read(uint16_t index, uint8_t subindex) {
    return sdo(encode_sdo_upload_request(node(), index, subindex));
  }
  Result<SdoMessage> sdo_write(uint16_t index, uint8_t subindex, uint32_t value, uint8_t size) {
    return sdo(encode_sdo_download_request(node(), index, subindex, value, size));
  }
  /// Writes and expects the confirmation.
  void write(uint16_t index, uint8_t subindex, uint32_t value, uint8_t size) {
    const auto r = sdo_write(index, subindex, value, size);
    ASSERT_TRUE(r.ok());
    ASSERT_EQ(r->type, SdoType::kDownloadResponse)
        << std::hex << "abort 0x" << r->abort_code << " writing 0x" << index << ":" << int{subindex};
  }

  /// One CSP cycle as a master runs it: RPDO1 (controlword, target), SYNC, then the drive runs
  /// for period_s. Returns the last TPDO1 of the cycle, if any arrived.
  std::optional<Feedback> cycle(uint16_t controlword, int32_t target_ticks, double period_s) {
    const uint64_t values[] = {controlword, static_cast<uint32_t>(target_ticks)};
    send(encode_pdo(rpdo_cob_id(1, node()), default_rpdo1(), values));
    send(encode_sync());
    clear_received();
    run(period_s);
    std::optional<Feedback> fb;
    for (const CanFrame& f : frames(tpdo_cob_id(1, node()))) fb = decode_feedback(f);
    if (fb) last_feedback_ = *fb;
    return fb;
  }

  /// Boots the drive, starts it, selects CSP and walks it to operation enabled with the
  /// master helper, holding the actual position as target. Returns the cycles it took.
  int bring_up(double period_s = 4e-3) {
    run(1e-3);  // boot-up
    send(encode_nmt(NmtCommand::kStart, node()));
    run(1e-3);
    write(cia402::od::kModesOfOperation, 0, static_cast<uint8_t>(cia402::kModeCyclicSynchronousPosition), 1);
    return enable(period_s);
  }

  /// Walks to operation enabled from wherever the drive is (at most 20 cycles).
  int enable(double period_s = 4e-3) {
    uint16_t cw = 0;
    uint16_t statusword = drive_->statusword();
    for (int i = 1; i <= 20; ++i) {
      cw = cia402::next_controlword(statusword, cw);
      const auto fb = cycle(cw, drive_->position_ticks(), period_s);
      if (!fb) return -1;
      statusword = fb->statusword;
      if (cia402::state_from_statusword(statusword) == cia402::State::kOperationEnabled) return i;
    }
    return -1;
  }

  const Feedback& last_feedback() const { return last_feedback_; }

 private:
  VirtualCanBus bus_;
  std::unique_ptr<VirtualCanEndpoint> master_;
  std::unique_ptr<VirtualCanEndpoint> drive_ep_;
  std::unique_ptr<EmulatedDrive> drive_;
  std::vector<CanFrame> received_;
  Feedback last_feedback_;
};

/// The drive's encoder ticks for an output angle.
inline int32_t ticks(const DriveRig& rig, double rad) {
  return static_cast<int32_t>(std::lround(rad * rig.drive().ticks_per_rad()));
}

/// The EMCY messages / heartbeats the master received.
inline std::vector<EmcyMessage> emcys(const DriveRig& rig) {
  std::vector<EmcyMessage> out;
  for (const CanFrame& f : rig.frames(cob::kEmcy + rig.node())) {
    const auto m = decode_emcy(f);
    EXPECT_TRUE(m.ok());
    if (m.ok()) out.push_back(*m);
  }
  return out;
}

inline std::vector<HeartbeatMessage> heartbeats(const DriveRig& rig) {
  std::vector<HeartbeatMessage> out;
  for (const CanFrame& f : rig.frames(cob::kHeartbeat + rig.node())) {
    const auto m = decode_heartbeat(f);
    EXPECT_TRUE(m.ok());
    if (m.ok()) out.push_back(*m);
  }
  return out;
}

/// The abort code of an SDO response that must be an abort.
inline uint32_t abort_of(const Result<SdoMessage>& r) {
  EXPECT_TRUE(r.ok());
  if (!r.ok()) return 0;
  EXPECT_EQ(r->type, SdoType::kAbort);
  return r->abort_code;
}

}  // namespace teleop::drive::test
