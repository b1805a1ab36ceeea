// Fault specs of the emulator's --inject option: parsing, errors, and what applying them does.
#include "teleop/hand/fault_schedule.h"

#include <gtest/gtest.h>

#include <linux/can/error.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "teleop/can/virtual_can_bus.h"

namespace teleop::hand {

using namespace can;  // the CANopen core the hand is built on
namespace {

std::string error_of(const std::string& spec) {
  try {
    parse_fault_spec(spec);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(FaultSchedule, ParsesEveryKind) {
  const ScheduledFault emcy_fault = parse_fault_spec("2.5:4:emcy:0x2310");
  EXPECT_DOUBLE_EQ(emcy_fault.at_s, 2.5);
  EXPECT_EQ(emcy_fault.node, 4);
  EXPECT_EQ(emcy_fault.kind, FaultKind::kEmcy);
  EXPECT_EQ(emcy_fault.value, 0x2310u);
  EXPECT_EQ(parse_fault_spec("1:9:drop-tpdo").value, drive::EmulatedDrive::kDropForever);
  EXPECT_EQ(parse_fault_spec("1:9:drop-tpdo:5").value, 5u);
  for (const char* kind : {"heartbeat-stop", "heartbeat-resume", "stall", "free", "tpdo-resume", "drop-rpdo",
                           "rpdo-resume", "refuse-sdo", "accept-sdo", "bus-off", "restarted"}) {
    EXPECT_STREQ(to_string(parse_fault_spec(std::string("0:1:") + kind).kind), kind);
  }
}

TEST(FaultSchedule, RejectsMalformedSpecsNamingTheProblem) {
  EXPECT_NE(error_of("1:4").find("expected 3 or 4 fields"), std::string::npos);
  EXPECT_NE(error_of("x:4:stall").find("time must be seconds"), std::string::npos);
  EXPECT_NE(error_of("1:0:stall").find("node must be 1..127"), std::string::npos);
  EXPECT_NE(error_of("1:128:stall").find("node must be 1..127"), std::string::npos);
  EXPECT_NE(error_of("1:4:explode").find("unknown kind 'explode'"), std::string::npos);
  EXPECT_NE(error_of("1:4:emcy").find("emcy needs an error code"), std::string::npos);
  EXPECT_NE(error_of("1:4:emcy:0x10000").find("emcy needs an error code"), std::string::npos);
  EXPECT_NE(error_of("1:4:stall:3").find("stall takes no value"), std::string::npos);
  EXPECT_NE(error_of("1:4:drop-tpdo:-2").find("positive number"), std::string::npos);
}

// records what is sent: error frames are what a SocketCAN raw socket (vcan) passes on, while
// the VirtualCanBus refuses them from applications
class RecordingBus final : public CanBus {
 public:
  CanStatus send(const CanFrame& frame) override {
    sent.push_back(frame);
    return CanStatus::kOk;
  }
  CanStatus receive(CanFrame&, std::chrono::nanoseconds) override { return CanStatus::kTimeout; }
  CanBusState state() const override { return CanBusState::kErrorActive; }
  CanBusStats stats() const override { return {}; }
  std::vector<CanFrame> sent;
};

TEST(FaultSchedule, AppliesToTheDriveOrSendsTheErrorFrame) {
  VirtualCanBus bus;
  auto drive_ep = bus.open("drive");
  auto observer = bus.open("observer");
  drive::EmulatedDriveConfig c;
  c.node_id = 3;
  drive::EmulatedDrive drive(*drive_ep, c);
  drive.step(1e-3);
  ASSERT_EQ(apply_fault(parse_fault_spec("0:3:emcy:0x7121"), drive, *drive_ep), CanStatus::kOk);
  EXPECT_EQ(drive.error_code(), 0x7121);
  ASSERT_EQ(apply_fault(parse_fault_spec("0:3:heartbeat-stop"), drive, *drive_ep), CanStatus::kOk);
  CanFrame f;
  while (observer->receive(f, std::chrono::nanoseconds::zero()) == CanStatus::kOk) {
  }
  drive.step(0.3);
  EXPECT_EQ(observer->receive(f, std::chrono::nanoseconds::zero()), CanStatus::kTimeout);  // no heartbeat
  RecordingBus recorder;
  ASSERT_EQ(apply_fault(parse_fault_spec("0:3:bus-off"), drive, recorder), CanStatus::kOk);
  ASSERT_EQ(apply_fault(parse_fault_spec("0:3:restarted"), drive, recorder), CanStatus::kOk);
  ASSERT_EQ(recorder.sent.size(), 2u);
  EXPECT_TRUE(recorder.sent[0].error());
  EXPECT_EQ(recorder.sent[0].id, static_cast<uint32_t>(CAN_ERR_BUSOFF));
  EXPECT_EQ(recorder.sent[1].id, static_cast<uint32_t>(CAN_ERR_RESTARTED));
}

}  // namespace
}  // namespace teleop::hand
