// leader.button_input against the kernel's input layer (leader/button_input.h), in the VM that has
// evdev and uinput (as vcan): a virtual USB e-stop button made with uinput is pressed, released,
// unplugged and plugged back; and the leader node, given it as its emergency stop, stops the bus
// with it and keeps the stop up while the button is gone.
#include <gtest/gtest.h>
#include <libevdev/libevdev-uinput.h>
#include <libevdev/libevdev.h>
#include <linux/input-event-codes.h>

#include <chrono>
#include <memory>
#include <stdexcept>
#include <thread>

#include "button_input.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/topics.h"
#include "vcan_support.h"
#include "vm_bus.h"
#include "vm_eventually.h"

namespace teleop::leader {
namespace {

using namespace std::chrono_literals;

constexpr const char* kName = "teleop test stop button";

// a USB button box with a pause key and one button, as the kernel sees one
class VirtualButton {
 public:
  VirtualButton() {
    libevdev* d = libevdev_new();
    libevdev_set_name(d, kName);
    libevdev_enable_event_type(d, EV_KEY);
    libevdev_enable_event_code(d, EV_KEY, KEY_PAUSE, nullptr);
    libevdev_enable_event_code(d, EV_KEY, BTN_0, nullptr);
    const int rc = libevdev_uinput_create_from_device(d, LIBEVDEV_UINPUT_OPEN_MANAGED, &uinput_);
    libevdev_free(d);
    if (rc != 0) throw std::runtime_error("uinput: " + std::string(strerror(-rc)));
    std::this_thread::sleep_for(300ms);  // udev-less VM: devtmpfs makes the node at once, give it a moment
  }
  ~VirtualButton() { libevdev_uinput_destroy(uinput_); }
  void key(unsigned code, int value) {
    libevdev_uinput_write_event(uinput_, EV_KEY, code, value);
    libevdev_uinput_write_event(uinput_, EV_SYN, SYN_REPORT, 0);
  }
  std::string node() const { return libevdev_uinput_get_devnode(uinput_); }

 private:
  libevdev_uinput* uinput_ = nullptr;
};

using test::eventually;

ButtonInputConfig by_name() { return {kName, {{KEY_PAUSE, 0}, {BTN_0, 3}}}; }

TEST(ButtonInputVm, PressReleaseUnplugAndReplug) {
  auto button = std::make_unique<VirtualButton>();
  ButtonInput input(by_name(), 1u << 0);
  EXPECT_TRUE(input.connected());
  EXPECT_NE(input.description().find(kName), std::string::npos) << input.description();
  EXPECT_EQ(input.word(), 0u);
  button->key(KEY_PAUSE, 1);
  EXPECT_TRUE(eventually([&] { return input.word() == 1u; }, 2000ms)) << input.word();
  button->key(BTN_0, 1);
  EXPECT_TRUE(eventually([&] { return input.word() == (1u | 1u << 3); }, 2000ms)) << input.word();
  button->key(KEY_PAUSE, 0);
  button->key(BTN_0, 0);
  EXPECT_TRUE(eventually([&] { return input.word() == 0u; }, 2000ms)) << input.word();
  // unplugged: the stop reads pressed until it is back
  button.reset();
  EXPECT_TRUE(eventually([&] { return !input.connected(); }, 2000ms));
  EXPECT_EQ(input.word(), 1u);
  EXPECT_EQ(input.losses(), 1u);
  button = std::make_unique<VirtualButton>();
  EXPECT_TRUE(eventually([&] { return input.connected(); }, 3000ms)) << "found again by its name";
  EXPECT_TRUE(eventually([&] { return input.word() == 0u; }, 2000ms)) << input.word();
}

TEST(ButtonInputVm, AKeyTheDeviceLacksOrNoDeviceIsAnErrorNamingIt) {
  VirtualButton button;
  try {
    ButtonInput input({button.node(), {{BTN_5, 0}}}, 0);
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("has no key BTN_5"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ButtonInput({"no such button box", {{KEY_PAUSE, 0}}}, 0), std::runtime_error);
}

TEST(ButtonInputVm, TheLeaderStopsTheBusWithTheButtonAndWhileItIsGone) {
  auto button = std::make_unique<VirtualButton>();
  const int domain = 40 + static_cast<int>(::getpid() % 100);
  transport::Participant participant(test::vm_participant(domain, "stop_watch"));
  auto stops = participant.make_reader(transport::topics::kEmergencyStop);
  can::test::ChildProcess leader({"teleop_leader", "--config", "leader", "--domain", std::to_string(domain), "--set",
                                  "node.rate_hz=100", "--set", "transport.initial_peers=[\"127.0.0.1\"]", "--set",
                                  "transport.interface_whitelist=[\"127.0.0.1\"]", "--set", "transport.discovery.mode=peers",
                                  "--set", std::string("leader.button_input={device: \"") + kName + "\", keys: {KEY_PAUSE: 0}}",
                                  "--set", "leader.buttons={emergency_stop: 0}"});
  // what arrives within `within`: the count of engaged stops, and the last one's origin
  const auto engaged_within = [&](std::chrono::milliseconds within, std::string& origin) {
    int engaged = 0;
    const auto until = std::chrono::steady_clock::now() + within;
    msg::EmergencyStop s;
    while (std::chrono::steady_clock::now() < until) {
      while (stops.take_next(s)) {
        if (s.engaged()) {
          ++engaged;
          origin = s.origin();
        }
      }
      std::this_thread::sleep_for(20ms);
    }
    return engaged;
  };
  // the leader is up once its status arrives (a minute for a slow VM)
  auto statuses = participant.make_reader(transport::topics::kNodeStatus);
  msg::NodeStatus status;
  ASSERT_TRUE(eventually([&] { return statuses.take_next(status); }, 60000ms)) << "the leader never came up";
  std::string origin;
  EXPECT_EQ(engaged_within(2s, origin), 0) << "a button at rest stops nothing";
  button->key(KEY_PAUSE, 1);
  EXPECT_GT(engaged_within(5s, origin), 0);
  EXPECT_NE(origin.find("button 0 of the leader's"), std::string::npos) << origin;
  button->key(KEY_PAUSE, 0);
  engaged_within(2s, origin);  // the last repeats drain
  EXPECT_EQ(engaged_within(3s, origin), 0) << "released: no more stops";
  button.reset();
  EXPECT_GT(engaged_within(5s, origin), 1) << "unplugged: the stop repeats while it is gone";
}

}  // namespace
}  // namespace teleop::leader
