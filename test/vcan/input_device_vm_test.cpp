// leader.device: spacemouse and gamepad against the kernel's input layer (leader/input_device.h),
// in the VM that has evdev and uinput: virtual devices made with uinput in the event maps of the
// real ones (a SpaceNavigator: 046d:c626, its cap on REL_X..REL_RZ about +-350 and BTN_0/BTN_1; an
// Xbox-class pad: sticks on ABS_X/Y/RX/RY over -32768..32767, BTN_TL/BTN_TR) move the device's
// pose at the configured speed, stop it when let go, and a device unplugged fails its reads until
// it is found again. And the stations as processes: the leader (pfc, the virtual SpaceNavigator)
// lifts the follower's simulated flange while the cap is held, and its unplug holds the follower.
#include <gtest/gtest.h>
#include <libevdev/libevdev-uinput.h>
#include <libevdev/libevdev.h>
#include <linux/input-event-codes.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "teleop/common/clock.h"
#include "teleop/experiment/trace.h"
#include "teleop/leader/device_registry.h"
#include "teleop/leader/input_devices.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/topics.h"
#include "vcan_support.h"
#include "vm_bus.h"
#include "vm_eventually.h"

namespace teleop::leader {
namespace {

using namespace std::chrono_literals;
using test::eventually;

// a device made with uinput: its name and id, and the axes and keys it reports
class VirtualDevice {
 public:
  VirtualDevice(const char* name, int vendor, int product, unsigned axis_type, const std::vector<unsigned>& axes,
                const std::vector<unsigned>& keys) {
    libevdev* d = libevdev_new();
    libevdev_set_name(d, name);
    libevdev_set_id_bustype(d, BUS_USB);
    libevdev_set_id_vendor(d, vendor);
    libevdev_set_id_product(d, product);
    input_absinfo stick{0, -32768, 32767, 16, 128, 0};
    for (unsigned a : axes) libevdev_enable_event_code(d, axis_type, a, axis_type == EV_ABS ? &stick : nullptr);
    for (unsigned k : keys) libevdev_enable_event_code(d, EV_KEY, k, nullptr);
    const int rc = libevdev_uinput_create_from_device(d, LIBEVDEV_UINPUT_OPEN_MANAGED, &uinput_);
    libevdev_free(d);
    if (rc != 0) throw std::runtime_error("uinput: " + std::string(strerror(-rc)));
    std::this_thread::sleep_for(300ms);  // udev-less VM: devtmpfs makes the node at once, give it a moment
  }
  ~VirtualDevice() { libevdev_uinput_destroy(uinput_); }
  // one report: the events, then SYN_REPORT
  void report(const std::vector<input_event>& events) {
    for (const input_event& e : events) libevdev_uinput_write_event(uinput_, e.type, e.code, e.value);
    libevdev_uinput_write_event(uinput_, EV_SYN, SYN_REPORT, 0);
  }

 private:
  libevdev_uinput* uinput_ = nullptr;
};

input_event event(unsigned type, unsigned code, int value) {
  input_event e{};
  e.type = static_cast<uint16_t>(type);
  e.code = static_cast<uint16_t>(code);
  e.value = value;
  return e;
}

std::unique_ptr<VirtualDevice> space_navigator() {
  return std::make_unique<VirtualDevice>("3Dconnexion SpaceNavigator", 0x046d, 0xc626, EV_REL,
                                         std::vector<unsigned>{REL_X, REL_Y, REL_Z, REL_RX, REL_RY, REL_RZ},
                                         std::vector<unsigned>{BTN_0, BTN_1});
}

// the leader's device as its configuration makes it (a 1 kHz loop)
std::unique_ptr<LeaderDevice> make(const std::string& yaml) {
  DeviceRegistry devices;
  add_input_devices(devices);
  const ConfigNode root = ConfigNode::load_string(yaml, "leader.yaml");
  DeviceSetup setup;
  setup.period_s = 1e-3;
  return devices.parse(root.child("leader"))->make(setup);
}

// a device sending a report every 8 ms while `sending`, as a held cap does
class Reporter {
 public:
  Reporter(VirtualDevice& device, std::vector<input_event> report) {
    thread_ = std::thread([&device, report, this] {
      while (sending_) {
        device.report(report);
        std::this_thread::sleep_for(8ms);
      }
    });
  }
  ~Reporter() { stop(); }
  void stop() {
    sending_ = false;
    if (thread_.joinable()) thread_.join();
  }

 private:
  std::atomic<bool> sending_{true};
  std::thread thread_;
};

TEST(InputDeviceVm, ASpaceNavigatorsHeldCapMovesThePoseAtItsSpeedAndItsReleaseStopsIt) {
  auto navigator = space_navigator();
  const auto device = make("leader:\n  device: spacemouse\n  spacemouse: {device: \"046d:c626\", linear_speed_mps: 0.1}\n");
  DeviceState state;
  ASSERT_TRUE(device->read(state));
  EXPECT_EQ(state.twist[0], 0.0) << "a cap at rest";
  // pushed fully along +x, half along -y (beyond the dead band of 0.1: 0.4 / 0.9 of full speed)
  Reporter held(*navigator, {event(EV_REL, REL_X, 350), event(EV_REL, REL_Y, -175)});
  ASSERT_TRUE(eventually([&] { return device->read(state) && state.twist[0] > 0.0; }, 3000ms));
  EXPECT_DOUBLE_EQ(state.twist[0], 0.1);
  EXPECT_NEAR(state.twist[1], -0.1 * 0.4 / 0.9, 1e-12);
  EXPECT_EQ(state.twist[2], 0.0);
  for (int i = 0; i < 200; ++i) {
    ASSERT_TRUE(device->read(state));
    std::this_thread::sleep_for(1ms);
  }
  EXPECT_GT(state.position_m[0], 0.0);
  EXPECT_NEAR(state.position_m[1] / state.position_m[0], -0.4 / 0.9, 0.2) << "moved along the deflection";
  EXPECT_EQ(state.position_m[2], 0.0);
  // let go: the kernel drops the zero values, the cap goes silent and reads as rest after release_ms
  held.stop();
  ASSERT_TRUE(eventually([&] { return device->read(state) && state.twist[0] == 0.0; }, 3000ms));
  const double stopped_at = state.position_m[0];
  for (int i = 0; i < 50; ++i) ASSERT_TRUE(device->read(state));
  EXPECT_EQ(state.position_m[0], stopped_at) << "at rest the pose holds";
}

TEST(InputDeviceVm, AGamepadsSticksAndButtonsMapByItsRangeAndTheDeflectionEndsWithTheStick) {
  VirtualDevice pad("Microsoft X-Box 360 pad", 0x045e, 0x028e, EV_ABS, {ABS_X, ABS_Y, ABS_RX, ABS_RY},
                    {BTN_TL, BTN_TR, BTN_SOUTH});
  const auto device = make("leader:\n  device: gamepad\n  gamepad: {device: \"Microsoft X-Box 360 pad\"}\n");
  DeviceState state;
  // the left stick fully up: forward (+x) at full speed; the right bumper: button 0
  pad.report({event(EV_ABS, ABS_Y, -32768), event(EV_KEY, BTN_TR, 1)});
  ASSERT_TRUE(eventually(
      [&] {
        state.buttons = 0;
        return device->read(state) && state.twist[0] > 0.04;
      },
      3000ms));
  EXPECT_NEAR(state.twist[0], 0.05, 1e-4) << "the default 0.05 m/s at full deflection";
  EXPECT_EQ(state.buttons, 1u << 0);
  // released: an absolute axis reports its return, the motion ends at once
  pad.report({event(EV_ABS, ABS_Y, 0), event(EV_KEY, BTN_TR, 0)});
  ASSERT_TRUE(eventually(
      [&] {
        state.buttons = 0;
        return device->read(state) && state.twist[0] == 0.0 && state.buttons == 0;
      },
      3000ms));
}

TEST(InputDeviceVm, AnUnpluggedDeviceFailsItsReadsUntilItIsFoundAgain) {
  auto navigator = space_navigator();
  const auto device = make("leader:\n  device: spacemouse\n  spacemouse: {device: \"3Dconnexion SpaceNavigator\"}\n");
  DeviceState state;
  ASSERT_TRUE(device->read(state));
  navigator.reset();
  ASSERT_TRUE(eventually([&] { return !device->read(state); }, 3000ms));
  EXPECT_EQ(state.twist[0], 0.0);
  navigator = space_navigator();
  EXPECT_TRUE(eventually([&] { return device->read(state); }, 5000ms)) << "found again by its name";
}

TEST(InputDeviceVm, ADeviceWithoutAConfiguredAxisIsRefusedNamingIt) {
  VirtualDevice pad("teleop test pad", 0x1234, 0x5678, EV_ABS, {ABS_X, ABS_Y}, {BTN_TR, BTN_TL});
  try {
    make("leader:\n  device: gamepad\n  gamepad: {device: \"teleop test pad\"}\n");
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("leader.gamepad: /dev/input/"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("has no axis ABS_RY"), std::string::npos) << e.what();
  }
  EXPECT_THROW(make("leader:\n  device: gamepad\n  gamepad: {device: \"no such pad\"}\n"), std::runtime_error);
}

// A node of the VM's bus (unicast on loopback), at 100 Hz (the emulator cannot keep 1 kHz), under
// pfc, with timeouts for a loop that the emulator starves now and then, and the Cartesian
// impedance softened for a 10 ms period: the shipped gains on the light wrist, stepped at 100 Hz,
// tripped the follower's speed reflex after a 0.14 s stall of a loaded VM (a CI run). The
// follower's hold too (its start holds the arm): 20 N m s/rad on the wrist at 10 ms tripped its
// speed reflex before the leader came (a CI run).
std::vector<std::string> node(const std::string& exe, const std::string& config, int domain, const std::string& trace,
                              std::vector<std::string> sets) {
  std::vector<std::string> args{exe, "--config", config, "--domain", std::to_string(domain), "--trace", trace};
  sets.insert(sets.end(), {"node.rate_hz=100", "teleoperation.architecture=pfc", "transport.initial_peers=[\"127.0.0.1\"]",
                           "transport.interface_whitelist=[\"127.0.0.1\"]", "transport.discovery.mode=peers"});
  for (const std::string& s : sets) args.insert(args.end(), {"--set", s});
  return args;
}

// the newest state a node of `role` reported on the bus (STARTING until one came)
class StatusWatch {
 public:
  StatusWatch(transport::Participant& p, msg::NodeRole role) : reader_(p.make_reader(transport::topics::kNodeStatus)), role_(role) {}
  msg::NodeState state() {
    msg::NodeStatus s;
    while (reader_.take_next(s)) {
      if (s.role() == role_) state_ = s.state();
    }
    return state_;
  }

 private:
  transport::Reader<msg::NodeStatus> reader_;
  msg::NodeRole role_;
  msg::NodeState state_ = msg::STATE_STARTING;
};

// the trace's value of `column` at the last row before `t_s` (CLOCK_MONOTONIC)
double at(const experiment::Trace& t, const std::string& column, double t_s) {
  const auto& c = t.column(column);
  double value = c.front();
  for (size_t i = 0; i < t.t_s.size() && t.t_s[i] < t_s; ++i) value = c[i];
  return value;
}

double monotonic_s() { return static_cast<double>(monotonic_now_ns()) * 1e-9; }

TEST(SpaceMouseTeleopVm, TheHeldCapLiftsTheFollowersFlangeAndItsUnplugHoldsIt) {
  auto navigator = space_navigator();
  const int domain = 40 + static_cast<int>(::getpid() % 100);
  transport::Participant participant(test::vm_participant(domain, "watch"));
  StatusWatch leader_state(participant, msg::ROLE_LEADER);
  const std::string dir = "/tmp/spacemouse_teleop";
  std::filesystem::create_directories(dir);
  can::test::ChildProcess follower(node("teleop_follower", "follower", domain, dir + "/follower.csv",
                                        {"follower.command_timeout_ms=500", "follower.hold_stiffness_nm_per_rad=50",
                                         "follower.hold_damping_nms_per_rad=1"}));
  can::test::ChildProcess leader(node("teleop_leader", "leader", domain, dir + "/leader.csv",
                                      {"leader.device=spacemouse", "leader.peer_timeout_ms=1000",
                                       "leader.cartesian={stiffness_n_per_m: [500, 500, 500], stiffness_nm_per_rad: [20, 20, 20], "
                                       "damping_ratio: 0.7, nullspace_stiffness_nm_per_rad: 2}",
                                       "leader.spacemouse={device: \"046d:c626\", linear_speed_mps: 0.05}"}));
  ASSERT_TRUE(eventually([&] { return leader_state.state() == msg::STATE_RUNNING; }, 120s)) << "the leader never ran";
  std::this_thread::sleep_for(1s);
  ASSERT_EQ(leader_state.state(), msg::STATE_RUNNING) << "the follower holds before the push (the VM's log says why)";
  // the cap pushed up (the default map: the kernel's REL_Z is the base frame's z) for 2 s
  const double pushed_s = monotonic_s();
  {
    Reporter held(*navigator, {event(EV_REL, REL_Z, 350)});
    std::this_thread::sleep_for(2s);
  }
  const double released_s = monotonic_s();
  std::this_thread::sleep_for(2s);  // the follower settles where the command stopped
  navigator.reset();
  ASSERT_TRUE(eventually([&] { return leader_state.state() == msg::STATE_SAFE_HOLD; }, 10s)) << "unplugged: held";
  const double unplugged_s = monotonic_s();
  std::this_thread::sleep_for(2s);
  const double end_s = monotonic_s();
  EXPECT_EQ(leader.stop(), 0);
  EXPECT_EQ(follower.stop(), 0);

  const experiment::Trace f = experiment::read_trace(dir + "/follower.csv");
  const experiment::Trace l = experiment::read_trace(dir + "/leader.csv");
  const double commanded_m = at(l, "x_cmd_z", end_s) - at(l, "x_cmd_z", pushed_s);
  const double lifted_m = at(f, "x_z", unplugged_s) - at(f, "x_z", pushed_s);
  std::printf("commanded %.4f m up, the flange rose %.4f m, moved %.4f m sideways\n", commanded_m, lifted_m,
              std::hypot(at(f, "x_x", unplugged_s) - at(f, "x_x", pushed_s), at(f, "x_y", unplugged_s) - at(f, "x_y", pushed_s)));
  // 0.05 m/s while held and for the release time after (the cap's last report stands that long),
  // less the cycles the emulator starved (the pose integrates per cycle run)
  EXPECT_GT(commanded_m, 0.02);
  EXPECT_LE(commanded_m, 0.05 * (released_s - pushed_s + 0.1) + 1e-3);
  EXPECT_NEAR(lifted_m, commanded_m, 0.01) << "the flange follows the command up";
  EXPECT_NEAR(at(f, "x_x", unplugged_s), at(f, "x_x", pushed_s), 0.01) << "along z only";
  EXPECT_NEAR(at(f, "x_y", unplugged_s), at(f, "x_y", pushed_s), 0.01) << "along z only";
  // unplugged: the command holds, and the flange with it (the impedance still settling by a few mm)
  EXPECT_EQ(at(l, "x_cmd_z", end_s), at(l, "x_cmd_z", unplugged_s));
  std::printf("unplugged: the flange moved %.4f m in the following %.1f s\n", at(f, "x_z", end_s) - at(f, "x_z", unplugged_s),
              end_s - unplugged_s);
  EXPECT_NEAR(at(f, "x_z", end_s), at(f, "x_z", unplugged_s), 0.005);
}

}  // namespace
}  // namespace teleop::leader
