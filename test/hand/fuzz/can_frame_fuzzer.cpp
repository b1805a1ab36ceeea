// libFuzzer target: arbitrary bytes as a stream of CAN frames, fed to every decoder of the
// CANopen stack and to the two components that consume frames from the bus, the hand adapter
// (master) and the emulated drive (slave). Checks, beyond "no crash, no sanitizer report":
// a frame that decodes re-encodes to the same frame, and the adapter's outputs stay finite.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "teleop/can/can_frame.h"
#include "teleop/can/cia301.h"
#include "teleop/can/cia402.h"
#include "teleop/drive/emulated_drive.h"
#include "teleop/hand/hand_adapter.h"

namespace {

using namespace teleop::can;
using namespace teleop::hand;

#define FUZZ_CHECK(condition) \
  do {                        \
    if (!(condition)) std::abort(); \
  } while (0)

// a bus that hands out the fuzzed frames and swallows what is sent
class ScriptedBus final : public CanBus {
 public:
  std::vector<CanFrame> frames;
  size_t next = 0;
  CanBusState bus_state = CanBusState::kErrorActive;
  CanStatus send(const CanFrame& frame) override { return frame.valid() ? CanStatus::kOk : CanStatus::kInvalidFrame; }
  CanStatus receive(CanFrame& frame, std::chrono::nanoseconds) override {
    if (next >= frames.size()) return CanStatus::kTimeout;
    frame = frames[next++];
    return CanStatus::kOk;
  }
  CanBusState state() const override { return bus_state; }
  CanBusStats stats() const override { return {}; }
};

// 12 bytes per frame: id (4, little-endian), dlc byte, flags byte, 6 data bytes (the last two
// data bytes repeat the first two, so 8-byte frames are reachable with less input)
CanFrame frame_from(const uint8_t* p) {
  CanFrame f;
  f.id = le::get_u32(p);
  f.dlc = p[4] & 0x0F;  // up to 15: invalid lengths too
  f.flags = p[5];
  for (int i = 0; i < 6; ++i) f.data[i] = p[6 + i];
  f.data[6] = p[6];
  f.data[7] = p[7];
  return f;
}

void decoders(const CanFrame& f) {
  (void)classify(f);
  (void)f.valid();
  if (const auto linux_frame = to_linux(f); linux_frame.ok()) {
    const auto back = from_linux(*linux_frame);
    FUZZ_CHECK(back.ok() && *back == f);
  }
  if (const auto m = decode_nmt(f); m.ok()) FUZZ_CHECK(*encode_nmt(m->command, m->node) == f);
  if (const auto m = decode_sync(f); m.ok()) FUZZ_CHECK(*encode_sync(m->counter) == f);
  if (const auto m = decode_emcy(f); m.ok()) FUZZ_CHECK(*encode_emcy(*m) == f);
  if (const auto m = decode_heartbeat(f); m.ok()) FUZZ_CHECK(*encode_heartbeat(m->node, m->state) == f);
  (void)decode_sdo_request(f);
  (void)decode_sdo_response(f);
  static const PdoMapping mapping = *PdoMapping::make({{0x6064, 0, 32}, {0x6078, 0, 16}, {0x6041, 0, 16}});
  uint64_t values[3];
  if (decode_pdo(f, mapping, values) == CanError::kNone && f.dlc == 8 && f.id <= CanFrame::kMaxStandardId) {
    const auto again = encode_pdo(static_cast<uint16_t>(f.id), mapping, values);
    FUZZ_CHECK(again.ok() && again->id == f.id && again->data == f.data);
  }
  const uint16_t cw = static_cast<uint16_t>(f.data[0] | (f.data[1] << 8));
  (void)cia402::state_from_statusword(cw);
  (void)cia402::command_from_controlword(cw, static_cast<uint16_t>(f.id));
  (void)cia402::next_controlword(cw, static_cast<uint16_t>(f.id));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  ScriptedBus adapter_bus;
  ScriptedBus drive_bus;
  for (size_t off = 0; off + 12 <= size; off += 12) {
    const CanFrame f = frame_from(data + off);
    decoders(f);
    adapter_bus.frames.push_back(f);
    drive_bus.frames.push_back(f);
  }
  // the adapter reads everything the bus hands it, in every phase the input can reach
  HandAdapter adapter(adapter_bus, HandAdapterConfig{});
  teleop::drive::EmulatedDriveConfig drive_config;
  drive_config.node_id = 3;
  teleop::drive::EmulatedDrive drive(drive_bus, drive_config);
  int64_t now = 0;
  while (adapter_bus.next < adapter_bus.frames.size() || drive_bus.next < drive_bus.frames.size()) {
    adapter_bus.bus_state = static_cast<CanBusState>(adapter_bus.next % 5 == 4 ? now % 5 : 0);
    adapter.cycle(now);
    drive.step(1e-3);
    now += 4'000'000;
    HandTargets t;
    t.position_rad.fill(static_cast<double>(now % 7) * 0.1);
    t.enable = (now / 4'000'000) % 3 != 0;
    t.fault_reset = (now / 4'000'000) % 2 == 0;
    adapter.set_command(t);
    for (double q : adapter.feedback().position_rad) FUZZ_CHECK(std::isfinite(q));
    for (double q : adapter.joint_positions()) FUZZ_CHECK(std::isfinite(q));
  }
  return 0;
}
