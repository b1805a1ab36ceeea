// The leader's devices by name (leader.device): the registry's choice and its errors, and a device
// registered by the test itself, built and driven by the leader from a configuration.
#include "teleop/leader/device_registry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "node_harness.h"
#include "teleop/leader/leader_arms.h"
#include "teleop/leader/simulated_devices.h"
#include "test_helpers.h"

namespace teleop::leader {
namespace {

// what the test's device saw: the leader's setup, its settings and the calls of the loop
struct Record {
  double gain = 0.0;
  DeviceSetup setup;
  int reads = 0;
  int writes = 0;
  int failing_reads = 0;  // the first reads that fail (a master arm's first state late)
  JointVector intent_q_rad{};
};

// a device of a lab's own: holds the pose its settings name, reports what the leader does with it
class RecordingDevice final : public LeaderDevice {
 public:
  RecordingDevice(std::shared_ptr<Record> record, JointVector pose_rad)
      : record_(std::move(record)), pose_rad_(pose_rad) {}
  size_t joints() const override { return record_->setup.joints; }
  void set_operator_intent(const OperatorIntent& intent) override { record_->intent_q_rad = intent.q_rad; }
  bool read(DeviceState& state) override {
    if (++record_->reads <= record_->failing_reads) return false;
    state.q_rad = pose_rad_;
    state.dq_radps.fill(0.0);
    return true;
  }
  bool write(const JointVector&) override {
    ++record_->writes;
    return true;
  }
  const char* name() const override { return "recording"; }

 private:
  std::shared_ptr<Record> record_;
  JointVector pose_rad_;
};

class RecordingSpec final : public DeviceSpec {
 public:
  RecordingSpec(std::shared_ptr<Record> record, JointVector pose_rad)
      : record_(std::move(record)), pose_rad_(pose_rad) {}
  const char* device() const override { return "recording"; }
  std::unique_ptr<LeaderDevice> make(const DeviceSetup& setup) const override {
    record_->setup = setup;
    return std::make_unique<RecordingDevice>(record_, pose_rad_);
  }

 private:
  std::shared_ptr<Record> record_;
  JointVector pose_rad_;
};

// the simulated devices and the test's own, `recording`, whose keys are leader.recording.{gain, pose_rad}
DeviceRegistry devices_with_recording(const std::shared_ptr<Record>& record) {
  DeviceRegistry devices;
  add_simulated_devices(devices);
  devices.add("recording", [record](const ConfigNode& section) {
    const ConfigNode own = section.child("recording");
    record->gain = own.get_double("gain", Range{0, 10});
    JointVector pose{};
    const auto values = own.get_double_list("pose_rad", Range{-3, 3});
    std::copy(values.begin(), values.end(), pose.begin());
    return std::make_shared<RecordingSpec>(record, pose);
  });
  return devices;
}

ConfigNode leader_section(const std::string& keys) {
  return ConfigNode::load_string("leader:\n  joints: 2\n" + keys, "leader.yaml").child("leader");
}

TEST(DeviceRegistry, BuildsTheDeviceTheConfigNamesFromItsOwnKeys) {
  auto record = std::make_shared<Record>();
  const DeviceRegistry devices = devices_with_recording(record);
  const auto spec =
      devices.parse(leader_section("  device: recording\n  recording: {gain: 2.5, pose_rad: [0.1, 0.2]}\n"));
  EXPECT_STREQ(spec->device(), "recording");
  EXPECT_EQ(record->gain, 2.5);
  EXPECT_EQ(devices.names(), (std::vector<std::string>{"scripted", "haptic_arm", "replay", "recording"}));
}

TEST(DeviceRegistry, ChoosesTheFirstRegisteredWhenTheConfigNamesNone) {
  EXPECT_STREQ(simulated_devices().parse(leader_section(""))->device(), "scripted");
}

TEST(DeviceRegistry, RefusesAnUnknownDeviceNamingTheRegisteredOnesAndTheNearest) {
  const auto refusal = [](const std::string& name) {
    return test::error_of<ConfigError>([&] { simulated_devices().parse(leader_section("  device: " + name + "\n")); });
  };
  EXPECT_EQ(refusal("hapticarm"),
            "leader.yaml:3: leader.device: 'hapticarm' is not one of: scripted, haptic_arm, replay (did you mean "
            "'haptic_arm'?)");
  // nothing near: the list alone
  EXPECT_EQ(refusal("omega"), "leader.yaml:3: leader.device: 'omega' is not one of: scripted, haptic_arm, replay");
}

TEST(DeviceRegistry, ChecksTheSettingsOfARegisteredDeviceTheConfigDoesNotUse) {
  auto record = std::make_shared<Record>();
  const DeviceRegistry devices = devices_with_recording(record);
  // kept for `--set leader.device=recording`: read, so they are no unknown keys ...
  const ConfigNode root =
      ConfigNode::load_string("leader:\n  recording: {gain: 1.5, pose_rad: [0, 0]}\n", "leader.yaml");
  EXPECT_STREQ(devices.parse(root.child("leader"))->device(), "scripted");
  EXPECT_EQ(record->gain, 1.5);
  EXPECT_NO_THROW(root.check_all_used());
  // ... and checked
  EXPECT_THROW(devices.parse(leader_section("  recording: {gain: 11, pose_rad: [0, 0]}\n")), ConfigError);
}

TEST(DeviceRegistry, RefusesADeviceRegisteredTwiceAndAnEmptyRegistry) {
  DeviceRegistry devices;
  EXPECT_THROW(devices.parse(leader_section("")), std::logic_error);
  add_simulated_devices(devices);
  EXPECT_THROW(devices.add("replay", [](const ConfigNode&) { return std::shared_ptr<const DeviceSpec>(); }),
               std::logic_error);
}

// the leader's node from a config naming the test's device: the device is built with the
// node's setup, read every cycle (once more at the start) and written every cycle, and the
// state it reports is the leader's device state
TEST(DeviceRegistry, TheLeaderDrivesADeviceTheTestRegistered) {
  auto record = std::make_shared<Record>();
  const DeviceRegistry devices = devices_with_recording(record);
  const ConfigNode root = ConfigNode::load_string(
      "teleoperation: {architecture: position_position}\n"
      "leader:\n"
      "  joints: 2\n"
      "  home_rad: [0.3, -0.4]\n"
      "  device: recording\n"
      "  recording: {gain: 1.0, pose_rad: [0.25, -0.5]}\n"
      "  feedback: {enabled: true}\n",
      "leader.yaml");
  const runtime::LogicBuilder build = leader_logic_parser(devices)(root);
  root.check_all_used();
  test::NodeHarness harness{"leader"};
  const std::unique_ptr<runtime::NodeLogic> node = build(harness.context);
  EXPECT_DOUBLE_EQ(record->setup.period_s, 1e-3);
  EXPECT_EQ(record->setup.joints, 2u);
  EXPECT_EQ(record->setup.home_rad[1], -0.4);
  EXPECT_EQ(record->intent_q_rad[0], 0.3) << "the script starts at home";
  for (int i = 0; i < 10; ++i) node->cycle(harness.tick());
  EXPECT_EQ(record->reads, 11);
  EXPECT_EQ(record->writes, 10);

  std::vector<std::string> columns;
  node->trace_columns(columns);
  std::vector<double> row(columns.size());
  node->trace_row(row.data());
  const auto q_dev_1 = std::find(columns.begin(), columns.end(), "q_dev_1");
  ASSERT_NE(q_dev_1, columns.end());
  EXPECT_EQ(row[static_cast<size_t>(q_dev_1 - columns.begin())], -0.5);
}

// a device that cannot be read at first (a master arm whose drives have not answered a SYNC yet)
// is a hardware fault while it cannot, not after it reads
TEST(DeviceRegistry, ADeviceIsAHardwareFaultWhileItCannotBeReadNotOnceItReads) {
  auto record = std::make_shared<Record>();
  record->failing_reads = 3;
  const DeviceRegistry devices = devices_with_recording(record);
  const ConfigNode root = ConfigNode::load_string(
      "teleoperation: {architecture: position_position}\nleader:\n  joints: 2\n  device: recording\n"
      "  recording: {gain: 1.0, pose_rad: [0.25, -0.5]}\n  feedback: {enabled: true}\n",
      "leader.yaml");
  test::NodeHarness harness{"leader"};
  const std::unique_ptr<runtime::NodeLogic> node = leader_logic_parser(devices)(root)(harness.context);
  const auto hardware_fault = [&] {
    std::vector<uint32_t> faults;
    node->active_faults(faults);
    return std::find(faults.begin(), faults.end(), msg::FAULT_HARDWARE) != faults.end();
  };
  node->cycle(harness.tick());
  EXPECT_TRUE(hardware_fault()) << "its second read failed";
  for (int i = 0; i < 3; ++i) node->cycle(harness.tick());
  EXPECT_FALSE(hardware_fault()) << "it reads now";
}

}  // namespace
}  // namespace teleop::leader
