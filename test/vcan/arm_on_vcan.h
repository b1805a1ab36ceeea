#pragma once
// The arm of CiA 402 drives on vcan, for the VM tests of its masters (the follower's, a leader's):
// the teleop_arm_emulator process and the node processes as children, an independent observer on
// the four buses (can_capture.h), the drives' states and positions read by an SDO client of the
// test's own, and what the frames say (arm_canopen_vcan_test.cpp tells why the VM runs the nodes
// at 100 Hz). The follower's configuration is the shipped example for the VM, holding the arm in
// a soft joint impedance.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "arm_vm_config.h"
#include "can_capture.h"
#include "canopen_hardware.h"
#include "canopen_sdo_client.h"
#include "teleop/can/cia402.h"
#include "teleop/common/config.h"
#include "teleop/common/data_paths.h"
#include "teleop/drive/drive_objects.h"
#include "teleop/robot/canopen_backend.h"
#include "vcan_support.h"

namespace teleop::robot::vm {

using can::Service;
using can::test::CanCapture;
using can::test::CapturedFrame;
using can::test::ChildProcess;
using can::test::arm_config_for_vm;
using can::test::arm_interfaces;
using can::test::logged;
using can::test::read_text;
using can::test::realtime_now_ns;
using can::test::replace_all;
using namespace std::chrono_literals;

// the VM's timing (arm_canopen_vcan_test.cpp)
constexpr int kHeartbeatMs = can::test::kVmHeartbeatMs;
constexpr int kLostAfterMs = can::test::kVmLostAfterMs;
// the follower's rate and its hold in the VM (arm_canopen_vcan_test.cpp)
constexpr int kNodeRateHz = 100;
constexpr int kHoldStiffnessNmPerRad = 50;
constexpr int kHoldDampingNmsPerRad = 2;

// The shipped example for the VM (arm_vm_config.h), the follower at its rate and holding in its
// soft impedance.
inline std::string follower_config(const std::string& dir) {
  std::string text = arm_config_for_vm(resolve_config("nodes", "follower_canopen_arm"), kNodeRateHz);
  replace_all(text, "hold_stiffness_nm_per_rad: 200\n", "hold_stiffness_nm_per_rad: " + std::to_string(kHoldStiffnessNmPerRad) + "\n");
  replace_all(text, "hold_damping_nms_per_rad: 20\n", "hold_damping_nms_per_rad: " + std::to_string(kHoldDampingNmsPerRad) + "\n");
  const std::string path = dir + "/follower_canopen_vcan.yaml";
  std::ofstream(path) << text;
  return path;
}

// One drive of the arm as the configuration places it: its bus (index into the interfaces) and id.
struct DriveAt {
  size_t bus = 0;
  can::NodeId node = 0;
};

// TPDO1 [0x6064 (4), 0x6077 (2), 0x6041 (2)]; RPDO1 [0x6040 (2), 0x6071 (2)]
inline uint16_t statusword(const can::CanFrame& f) { return static_cast<uint16_t>(f.data[6] | f.data[7] << 8); }
inline uint16_t controlword(const can::CanFrame& f) { return static_cast<uint16_t>(f.data[0] | f.data[1] << 8); }
inline can::cia402::State reported_state(const CapturedFrame& tpdo) {
  return can::cia402::state_from_statusword(statusword(tpdo.frame));
}
// enable voltage set, quick stop (active low) clear: transition 11 from operation enabled
inline bool asks_quick_stop(const CapturedFrame& rpdo) {
  const uint16_t cw = controlword(rpdo.frame);
  return (cw & can::cia402::cw::kEnableVoltage) != 0 && (cw & can::cia402::cw::kQuickStop) == 0;
}

/// The first frame of `service` from/to `drive` after t_ns matching `match`; null when none.
template <typename Match>
inline const CapturedFrame* first_after(const std::vector<CapturedFrame>& frames, const DriveAt& drive, Service service,
                                 int64_t t_ns, Match match) {
  for (const CapturedFrame& c : frames) {
    if (c.t_ns > t_ns && can::test::is(c, drive.bus, service, drive.node) && match(c)) return &c;
  }
  return nullptr;
}

/// The RPDO from which on the master asked `drive` for its quick stop until the end of the
/// capture (a fault holds for good); null when the last RPDO asks for something else.
inline const CapturedFrame* lasting_quick_stop(const std::vector<CapturedFrame>& frames, const DriveAt& drive) {
  const CapturedFrame* since = nullptr;
  for (const CapturedFrame& c : frames) {
    if (!can::test::is(c, drive.bus, Service::kRpdo, drive.node)) continue;
    if (!asks_quick_stop(c)) {
      since = nullptr;
    } else if (since == nullptr) {
      since = &c;
    }
  }
  return since;
}

/// The newest frame on `bus` from `node` of `service` at or before t_ns; 0 when none.
inline int64_t last_before(const std::vector<CapturedFrame>& frames, size_t bus, Service service, can::NodeId node,
                    int64_t t_ns) {
  int64_t last = 0;
  for (const CapturedFrame& c : frames) {
    if (c.t_ns <= t_ns && can::test::is(c, bus, service, node)) last = c.t_ns;
  }
  return last;
}

// The arm on vcan: the emulator and the follower as processes, and the observer.
class ArmOnVcan : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = "/tmp/arm_vcan_" + std::to_string(::getpid()) + "_" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::filesystem::create_directories(dir_);
    config_path_ = follower_config(dir_);
    config_ = parse_canopen_hardware(ConfigNode::load_file(config_path_).child("follower"))->config();
    const std::vector<std::string> names = arm_interfaces();
    for (const CanopenJointConfig& j : config_.joints) {
      const size_t bus = static_cast<size_t>(std::find(names.begin(), names.end(), j.bus) - names.begin());
      drives_.push_back({bus, j.node});
    }
    capture_ = std::make_unique<CanCapture>(names);
  }

  void TearDown() override {
    leader_.reset();
    follower_.reset();
    emulator_.reset();
    if (HasFailure()) std::printf("%s", logs().c_str());
  }

  // the drives are hardware of their own: in the shared VM their emulator goes before the nodes
  void start_emulator(std::vector<std::string> more = {}) {
    std::vector<std::string> args{"teleop_arm_emulator", "--drives", config_path_};
    args.insert(args.end(), more.begin(), more.end());
    emulator_ = std::make_unique<ChildProcess>(logged(args, log("emulator")));
    ASSERT_TRUE(emulator_->set_nice(-10));
  }
  /// The emulator, then the follower, until every drive answers the SYNC in operation enabled:
  /// the follower holds the arm by its torques (no leader: its watchdog's hold).
  void start_all() {
    start_emulator();
    if (HasFatalFailure()) return;
    follower_ = std::make_unique<ChildProcess>(
        logged({"teleop_follower", "--config", config_path_, "--domain", domain(), "--report", log("follower_report")},
               log("follower")));
    ASSERT_TRUE(wait_for([&] { return all_drives_in(can::cia402::State::kOperationEnabled); }, 240s))
        << "the drives never all reached operation enabled";
    std::this_thread::sleep_for(1s);
    ASSERT_TRUE(all_drives_in(can::cia402::State::kOperationEnabled)) << "the drives did not stay enabled";
  }

  std::string domain() const { return std::to_string(80 + ::getpid() % 50); }
  std::string log(const std::string& who) const { return dir_ + "/" + who + ".log"; }
  /// The processes' output without the VM's stall warnings, the last 40 lines of each.
  std::string logs() const {
    std::string out;
    for (const char* who : {"emulator", "follower", "follower_report", "leader", "leader_report"}) {
      std::istringstream in(read_text(log(who)));
      std::vector<std::string> lines;
      for (std::string line; std::getline(in, line);) {
        if (line.find("the loop stalled") == std::string::npos) lines.push_back(line);
      }
      out += std::string("--- ") + who + "\n";
      for (size_t k = lines.size() > 40 ? lines.size() - 40 : 0; k < lines.size(); ++k) out += lines[k] + "\n";
    }
    return out;
  }

  template <typename F>
  static bool wait_for(F condition, std::chrono::seconds limit) {
    const auto end = std::chrono::steady_clock::now() + limit;
    while (!condition()) {
      if (std::chrono::steady_clock::now() > end) return false;
      std::this_thread::sleep_for(50ms);
    }
    return true;
  }

  /// The newest TPDO1 of each drive (but `except`) reports `state`.
  bool all_drives_in(can::cia402::State state, can::NodeId except = 0) const {
    for (const DriveAt& d : drives_) {
      CapturedFrame tpdo;
      if (d.node == except) continue;
      if (!capture_->latest(d.bus, Service::kTpdo, d.node, tpdo) || reported_state(tpdo) != state) return false;
    }
    return true;
  }

  /// Calls f(sdo) with an SDO client of this test's own to `drive` (its answers only).
  template <typename F>
  static void with_sdo(const DriveAt& drive, F f) {
    can::SocketCanBus bus(arm_interfaces()[drive.bus], {.filters = {{static_cast<uint32_t>(0x580 + drive.node), 0x7FF}}});
    SdoWait wait;
    wait.timeout = 5s;  // the emulator answers from a starved VM
    SdoClient sdo(bus, wait);
    f(sdo);
  }

  /// Writes the emulator's fault injection object of `drive`.
  void inject(const DriveAt& drive, uint8_t subindex, uint32_t value) {
    with_sdo(drive, [&](SdoClient& sdo) { sdo.write(drive.node, drive::drive_od::kFaultInjection, subindex, value, 4); });
  }

  /// Every drive's state (0x6041) and position (0x6064, ticks), read by SDO.
  std::vector<std::pair<can::cia402::State, int32_t>> read_drives() {
    std::vector<std::pair<can::cia402::State, int32_t>> out;
    for (const DriveAt& d : drives_) {
      with_sdo(d, [&](SdoClient& sdo) {
        const auto sw = static_cast<uint16_t>(sdo.read(d.node, can::cia402::od::kStatusword, 0));
        const auto q = static_cast<int32_t>(sdo.read(d.node, can::cia402::od::kPositionActualValue, 0));
        out.emplace_back(can::cia402::state_from_statusword(sw), q);
      });
    }
    return out;
  }

  /// Every drive in its quick stop, holding its joint: 1 s later within 0.5 mrad (read by SDO: with
  /// the master gone there is no SYNC, so no TPDO).
  void expect_every_drive_stopped_and_holding() {
    const auto first = read_drives();
    std::this_thread::sleep_for(1s);
    const auto second = read_drives();
    for (size_t k = 0; k < drives_.size(); ++k) {
      SCOPED_TRACE("joint " + std::to_string(k + 1));
      EXPECT_EQ(first[k].first, can::cia402::State::kQuickStopActive) << can::cia402::to_string(first[k].first);
      const double ticks_per_rad = config_.joints[k].axis.gear_ratio * config_.joints[k].axis.encoder_ticks_per_rev / (2 * M_PI);
      EXPECT_NEAR(second[k].second, first[k].second, 5e-4 * ticks_per_rad);
    }
  }

  std::string dir_;
  std::string config_path_;
  CanopenHardwareConfig config_;
  std::vector<DriveAt> drives_;
  std::unique_ptr<CanCapture> capture_;
  std::unique_ptr<ChildProcess> emulator_;
  std::unique_ptr<ChildProcess> follower_;
  std::unique_ptr<ChildProcess> leader_;
};

}  // namespace teleop::robot::vm
