// HIL tests of SocketCanBus on a virtual CAN interface (vcan0, or $TELEOP_VCAN_IF). They need a
// kernel with vcan and an interface that is up, plus can-utils (cansend, candump) and
// teleop_hand_emulator on PATH: test/vcan/run_in_vm.sh provides all of it, in a qemu VM when
// this host's kernel has no CAN. Run directly only where vcan0 exists.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <string>
#include <thread>

#include "teleop/can/cia301.h"
#include "teleop/can/socketcan_bus.h"
#include "teleop/drive/emulated_drive.h"
#include "vcan_support.h"

namespace teleop::can {
namespace {

using namespace std::chrono_literals;

using test::iface;
using drive::EmulatedDrive;
using drive::EmulatedDriveConfig;

CanFrame frame(uint32_t id, std::initializer_list<uint8_t> bytes) {
  CanFrame f;
  f.id = id;
  f.dlc = static_cast<uint8_t>(bytes.size());
  size_t i = 0;
  for (auto b : bytes) f.data[i++] = b;
  return f;
}

// receives until a frame with `id` arrives (other frames are skipped) or the time is up
bool receive_id(SocketCanBus& bus, uint32_t id, CanFrame& out, std::chrono::milliseconds within = 2000ms,
                int64_t* ts = nullptr) {
  const auto end = std::chrono::steady_clock::now() + within;
  while (std::chrono::steady_clock::now() < end) {
    int64_t t = 0;
    if (bus.receive(out, 50ms, t) == CanStatus::kOk && !out.error() && out.id == id) {
      if (ts != nullptr) *ts = t;
      return true;
    }
  }
  return false;
}

int64_t realtime_ns() {
  timespec t{};
  ::clock_gettime(CLOCK_REALTIME, &t);
  return t.tv_sec * 1000000000LL + t.tv_nsec;
}

TEST(SocketCanVcan, TwoEndpointsExchangeFramesWithKernelTimestamps) {
  SocketCanBus a(iface());
  SocketCanBus b(iface());
  EXPECT_EQ(a.state(), CanBusState::kErrorActive);
  const auto sent = frame(0x123, {1, 2, 3, 4, 5, 6, 7, 8});
  const int64_t before = realtime_ns();
  ASSERT_EQ(a.send(sent), CanStatus::kOk);
  CanFrame got;
  int64_t ts = 0;
  ASSERT_TRUE(receive_id(b, 0x123, got, 2000ms, &ts));
  EXPECT_EQ(got, sent);
  EXPECT_GE(ts, before - 1000000);  // kernel timestamp of reception, CLOCK_REALTIME
  EXPECT_LE(ts, realtime_ns() + 1000000);
  // extended id, back the other way; a sender does not receive its own frames by default
  CanFrame ext = frame(0x1ABCDE0, {0xAA});
  ext.flags = CanFrame::kExtended;
  ASSERT_EQ(b.send(ext), CanStatus::kOk);
  ASSERT_TRUE(receive_id(a, 0x1ABCDE0, got));
  EXPECT_TRUE(got.extended());
  EXPECT_EQ(b.receive(got, 50ms), CanStatus::kTimeout);
  EXPECT_EQ(a.stats().tx_frames, 1u);
  EXPECT_GE(b.stats().rx_frames, 1u);
  // invalid frames are refused without reaching the socket
  EXPECT_EQ(a.send(frame(0x800, {})), CanStatus::kInvalidFrame);
  EXPECT_EQ(a.stats().tx_dropped, 1u);
}

TEST(SocketCanVcan, NodeFiltersPassOnlyTheNodesFrames) {
  SocketCanBus sender(iface());
  SocketCanOptions options;
  options.filters = canopen_node_filters(5);
  SocketCanBus node5(iface(), options);
  ASSERT_EQ(sender.send(frame(0x606, {0x40, 0, 0x10, 0, 0, 0, 0, 0})), CanStatus::kOk);  // node 6's SDO
  ASSERT_EQ(sender.send(frame(0x185, {1})), CanStatus::kOk);                             // a TPDO
  ASSERT_EQ(sender.send(frame(0x605, {0x40, 0, 0x10, 0, 0, 0, 0, 0})), CanStatus::kOk);  // node 5's SDO
  CanFrame got;
  ASSERT_EQ(node5.receive(got, 1s), CanStatus::kOk);
  EXPECT_EQ(got.id, 0x605u);
  EXPECT_EQ(node5.receive(got, 50ms), CanStatus::kTimeout);
  // back to everything
  node5.set_filters({});
  ASSERT_EQ(sender.send(frame(0x185, {2})), CanStatus::kOk);
  ASSERT_TRUE(receive_id(node5, 0x185, got));
}

TEST(SocketCanVcan, ReceiveQueueOverflowIsCounted) {
  SocketCanBus sender(iface());
  SocketCanOptions options;
  options.receive_buffer_bytes = 1;  // the kernel rounds up to its minimum: a few frames
  SocketCanBus slow(iface(), options);
  unsigned sent = 0;
  for (int i = 0; i < 2000; ++i) {
    if (sender.send(frame(0x321, {static_cast<uint8_t>(i)})) == CanStatus::kOk) ++sent;
    // local delivery goes through the per-CPU backlog (netdev_max_backlog, 1000): let it drain
    if (i % 50 == 49) std::this_thread::sleep_for(1ms);
  }
  EXPECT_GT(sent, 100u);
  CanFrame got;
  unsigned received = 0;
  while (slow.receive(got, 100ms) == CanStatus::kOk) ++received;
  EXPECT_LT(received, sent);
  // the kernel stamps its drop count on each frame as it queues it: the frames queued before
  // the overflow carry the old count, so one more frame after the flood reports the drops
  ASSERT_EQ(sender.send(frame(0x321, {0xFF})), CanStatus::kOk);
  ++sent;
  while (slow.receive(got, 100ms) == CanStatus::kOk) ++received;
  EXPECT_GT(slow.stats().rx_overruns, 0u);
  // every frame lost at this socket is counted; a frame can still be lost before it (in the
  // backlog, under load), so the sum may fall short of `sent`, never exceed it
  EXPECT_LE(received + slow.stats().rx_overruns, sent) << "received " << received;
  EXPECT_GT(received + slow.stats().rx_overruns, sent / 2) << "received " << received;
}

TEST(SocketCanVcan, EmulatedDriveBootsAndAnswersSdoUpload) {
  SocketCanBus master(iface());
  SocketCanOptions options;
  options.filters = canopen_node_filters(3);
  SocketCanBus drive_bus(iface(), options);
  drive::EmulatedDriveConfig config;
  config.node_id = 3;
  drive::EmulatedDrive drive(drive_bus, config);
  std::atomic<bool> stop{false};
  std::thread stepper([&] {
    while (!stop) {
      drive.step(0.001);
      std::this_thread::sleep_for(1ms);
    }
  });
  CanFrame got;
  EXPECT_TRUE(receive_id(master, 0x703, got));  // boot-up
  EXPECT_EQ(got.dlc, 1);
  EXPECT_EQ(got.data[0], 0);
  ASSERT_EQ(master.send(encode_sdo_upload_request(3, 0x1000, 0).value()), CanStatus::kOk);
  ASSERT_TRUE(receive_id(master, 0x583, got));
  const auto response = decode_sdo_response(got);
  ASSERT_TRUE(response.ok());
  EXPECT_EQ(response->type, SdoType::kUploadResponse);
  EXPECT_EQ(response->data, drive::EmulatedDrive::kDeviceType);
  // NMT start: the heartbeat then reports operational (0x05)
  ASSERT_EQ(master.send(encode_nmt(NmtCommand::kStart, 3).value()), CanStatus::kOk);
  bool operational = false;
  for (int i = 0; i < 20 && !operational; ++i) {
    operational = receive_id(master, 0x703, got, 500ms) && got.data[0] == 0x05;
  }
  EXPECT_TRUE(operational);
  stop = true;
  stepper.join();
  EXPECT_GE(drive.stats().sdo_requests, 1u);
}

TEST(SocketCanVcan, CansendFramesReachOurBus) {
  SocketCanBus bus(iface());
  const std::string cmd = "cansend " + iface() + " 000#0105";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  CanFrame got;
  ASSERT_TRUE(receive_id(bus, 0x000, got));
  const auto nmt = decode_nmt(got);
  ASSERT_TRUE(nmt.ok());
  EXPECT_EQ(nmt->command, NmtCommand::kStart);
  EXPECT_EQ(nmt->node, 5);
}

// vcan has no controller, but error frames written to it (cansend with CAN_ERR_FLAG in the id)
// reach every socket whose CAN_RAW_ERR_FILTER matches, as a driver's would
TEST(SocketCanVcan, ErrorFramesSetTheBusState) {
  SocketCanBus bus(iface());
  auto inject = [&](const std::string& text, CanBusState expected) {
    const std::string cmd = "cansend " + iface() + " " + text;
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    CanFrame got;
    const auto end = std::chrono::steady_clock::now() + 2s;
    bool seen = false;
    while (!seen && std::chrono::steady_clock::now() < end) {
      seen = bus.receive(got, 50ms) == CanStatus::kOk && got.error();
    }
    ASSERT_TRUE(seen) << cmd;
    EXPECT_EQ(bus.state(), expected) << cmd;
  };
  inject("20000004#0004000000000000", CanBusState::kErrorWarning);  // controller: rx warning
  inject("20000004#0010000000000000", CanBusState::kErrorPassive);  // controller: rx passive
  inject("20000040#0000000000000000", CanBusState::kBusOff);        // bus-off
  EXPECT_EQ(bus.send(frame(0x123, {1})), CanStatus::kBusOff);
  inject("20000100#0000000000000000", CanBusState::kErrorActive);   // restarted
  EXPECT_EQ(bus.send(frame(0x123, {1})), CanStatus::kOk);
  const auto s = bus.socket_stats();
  EXPECT_EQ(s.bus.error_frames, 4u);
  EXPECT_EQ(s.controller_problems, 2u);
  EXPECT_EQ(s.bus_off_events, 1u);
  EXPECT_EQ(s.restarts, 1u);
  EXPECT_EQ(s.bus.tx_dropped, 1u);
}

TEST(SocketCanVcan, CandumpSeesOurSyncFrames) {
  SocketCanBus bus(iface());
  const std::string cmd = "timeout 10 candump -L -n 3 " + iface() + ",080:7FF";
  FILE* pipe = ::popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::atomic<bool> done{false};
  std::string output;
  std::thread reader([&] {
    char line[256];
    while (std::fgets(line, sizeof(line), pipe) != nullptr) output += line;
    done = true;
  });
  // candump has to bind before it can see anything: keep sending SYNC until it has its 3
  uint8_t counter = 1;
  for (int i = 0; i < 1000 && !done; ++i) {
    ASSERT_EQ(bus.send(encode_sync(counter).value()), CanStatus::kOk);
    counter = static_cast<uint8_t>(counter % 240 + 1);
    std::this_thread::sleep_for(10ms);
  }
  reader.join();
  const int status = ::pclose(pipe);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << output;
  size_t lines = 0;
  for (size_t p = output.find(iface() + " 080#"); p != std::string::npos; p = output.find(iface() + " 080#", p + 1)) {
    ++lines;
  }
  EXPECT_EQ(lines, 3u) << output;
}

TEST(SocketCanVcan, HandEmulatorProcessAnswersEveryNode) {
  SocketCanBus master(iface());
  test::EmulatorProcess emulator({"--nodes", "1-9", "--duration", "30"});
  ASSERT_TRUE(emulator.started());
  int answered = 0;
  for (uint8_t node = 1; node <= 9; ++node) {
    // the emulator may still be starting: repeat the request until its answer comes
    for (int attempt = 0; attempt < 20; ++attempt) {
      ASSERT_EQ(master.send(encode_sdo_upload_request(node, 0x1018, 4).value()), CanStatus::kOk);
      CanFrame got;
      if (receive_id(master, 0x580u + node, got, 500ms)) {
        const auto r = decode_sdo_response(got);
        ASSERT_TRUE(r.ok());
        EXPECT_EQ(r->data, node) << "serial number of node " << int{node};
        ++answered;
        break;
      }
    }
  }
  const int status = emulator.stop();
  EXPECT_EQ(answered, 9);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "emulator status " << status;
}

// can-utils against the emulator process: candump sees the nine heartbeats, an NMT start for
// all nodes sent with cansend turns every heartbeat to operational (0x05)
TEST(SocketCanVcan, CanUtilsTalkToTheHandEmulator) {
  SocketCanBus master(iface());
  test::EmulatorProcess emulator({"--duration", "30"});
  ASSERT_TRUE(emulator.started());
  const std::string dump = "timeout 10 candump -L -n 27 " + iface() + ",700:780";
  FILE* pipe = ::popen(dump.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::set<std::string> ids;
  char line[256];
  while (std::fgets(line, sizeof(line), pipe) != nullptr) {
    const std::string l = line;
    const auto p = l.find(iface() + " 7");
    if (p != std::string::npos) ids.insert(l.substr(p + iface().size() + 1, 3));
  }
  EXPECT_EQ(::pclose(pipe), 0);
  EXPECT_EQ(ids.size(), 9u) << "heartbeat ids seen by candump: " << ids.size();
  ASSERT_EQ(std::system(("cansend " + iface() + " 000#0100").c_str()), 0);
  std::set<uint32_t> operational;
  const auto end = std::chrono::steady_clock::now() + 3s;
  while (operational.size() < 9 && std::chrono::steady_clock::now() < end) {
    CanFrame got;
    if (master.receive(got, 50ms) == CanStatus::kOk && got.id > 0x700 && got.id <= 0x709 && got.dlc == 1 &&
        got.data[0] == 0x05) {
      operational.insert(got.id);
    }
  }
  const int status = emulator.stop();
  EXPECT_EQ(operational.size(), 9u);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "emulator status " << status;
}

}  // namespace
}  // namespace teleop::can
