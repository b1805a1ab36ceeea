#include "teleop/hand/fault_schedule.h"

#include <linux/can/error.h>

#include <cstdlib>
#include <stdexcept>
#include <vector>

namespace teleop::hand {

using can::CanBus;
using can::CanFrame;
using can::CanStatus;
using can::kMaxNodeId;
using can::NodeId;
using can::valid_node;

namespace {

struct KindName {
  const char* name;
  FaultKind kind;
  bool takes_value;
};

constexpr KindName kKinds[] = {
    {"heartbeat-stop", FaultKind::kHeartbeatStop, false}, {"heartbeat-resume", FaultKind::kHeartbeatResume, false},
    {"emcy", FaultKind::kEmcy, true},                     {"stall", FaultKind::kStall, false},
    {"free", FaultKind::kFree, false},                    {"drop-tpdo", FaultKind::kDropTpdo, true},
    {"tpdo-resume", FaultKind::kTpdoResume, false},       {"drop-rpdo", FaultKind::kDropRpdo, true},
    {"rpdo-resume", FaultKind::kRpdoResume, false},       {"refuse-sdo", FaultKind::kRefuseSdo, false},
    {"accept-sdo", FaultKind::kAcceptSdo, false},         {"bus-off", FaultKind::kBusOff, false},
    {"restarted", FaultKind::kRestarted, false},
};

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (size_t p = s.find(sep); p != std::string::npos; p = s.find(sep, start)) {
    parts.push_back(s.substr(start, p - start));
    start = p + 1;
  }
  parts.push_back(s.substr(start));
  return parts;
}

// a whole number (decimal or 0x hex) within [0, max]
bool parse_number(const std::string& text, uint64_t max, uint64_t& out) {
  if (text.empty()) return false;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 0);
  if (*end != '\0' || v > max || text[0] == '-') return false;
  out = v;
  return true;
}

CanFrame error_frame(uint32_t error_class) {
  CanFrame f;
  f.id = error_class;
  f.flags = CanFrame::kError;
  f.dlc = CAN_ERR_DLC;
  return f;
}

}  // namespace

const char* to_string(FaultKind kind) {
  for (const KindName& k : kKinds) {
    if (k.kind == kind) return k.name;
  }
  return "?";
}

ScheduledFault parse_fault_spec(const std::string& spec) {
  const auto fail = [&](const std::string& problem) {
    return std::invalid_argument("fault '" + spec + "': " + problem + " (SECONDS:NODE:KIND[:VALUE])");
  };
  const std::vector<std::string> parts = split(spec, ':');
  if (parts.size() < 3 || parts.size() > 4) throw fail("expected 3 or 4 fields");
  ScheduledFault f;
  char* end = nullptr;
  f.at_s = std::strtod(parts[0].c_str(), &end);
  if (parts[0].empty() || *end != '\0' || !(f.at_s >= 0) || f.at_s > 1e6) throw fail("time must be seconds >= 0");
  uint64_t node = 0;
  if (!parse_number(parts[1], kMaxNodeId, node) || !valid_node(static_cast<NodeId>(node))) {
    throw fail("node must be 1..127");
  }
  f.node = static_cast<NodeId>(node);
  const KindName* kind = nullptr;
  for (const KindName& k : kKinds) {
    if (parts[2] == k.name) kind = &k;
  }
  if (kind == nullptr) throw fail("unknown kind '" + parts[2] + "'");
  f.kind = kind->kind;
  if (parts.size() == 4 && !kind->takes_value) throw fail(parts[2] + " takes no value");
  if (f.kind == FaultKind::kEmcy) {
    uint64_t code = 0;
    if (parts.size() != 4 || !parse_number(parts[3], 0xFFFF, code) || code == 0) {
      throw fail("emcy needs an error code 0x0001..0xFFFF");
    }
    f.value = static_cast<uint32_t>(code);
  } else if (kind->takes_value) {
    uint64_t count = drive::EmulatedDrive::kDropForever;
    if (parts.size() == 4 && (!parse_number(parts[3], 0xFFFFFFFE, count) || count == 0)) {
      throw fail("the count must be a positive number");
    }
    f.value = static_cast<uint32_t>(count);
  }
  return f;
}

CanStatus apply_fault(const ScheduledFault& fault, drive::EmulatedDrive& drive, CanBus& bus) {
  switch (fault.kind) {
    case FaultKind::kHeartbeatStop:
    case FaultKind::kHeartbeatResume:
      drive.set_heartbeat_suppressed(fault.kind == FaultKind::kHeartbeatStop);
      break;
    case FaultKind::kEmcy:
      drive.raise_fault(static_cast<uint16_t>(fault.value));
      break;
    case FaultKind::kStall:
    case FaultKind::kFree:
      drive.set_stalled(fault.kind == FaultKind::kStall);
      break;
    case FaultKind::kDropTpdo:
    case FaultKind::kTpdoResume:
      drive.drop_tpdos(fault.kind == FaultKind::kDropTpdo ? fault.value : 0);
      break;
    case FaultKind::kDropRpdo:
    case FaultKind::kRpdoResume:
      drive.drop_rpdos(fault.kind == FaultKind::kDropRpdo ? fault.value : 0);
      break;
    case FaultKind::kRefuseSdo:
    case FaultKind::kAcceptSdo:
      drive.set_sdo_refused(fault.kind == FaultKind::kRefuseSdo);
      break;
    case FaultKind::kBusOff:
      return bus.send(error_frame(CAN_ERR_BUSOFF));
    case FaultKind::kRestarted:
      return bus.send(error_frame(CAN_ERR_RESTARTED));
  }
  return CanStatus::kOk;
}

}  // namespace teleop::hand
