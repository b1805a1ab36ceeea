#include "teleop/can/can_bus.h"

namespace teleop::can {

const char* to_string(CanStatus status) {
  switch (status) {
    case CanStatus::kOk:
      return "ok";
    case CanStatus::kTimeout:
      return "timeout";
    case CanStatus::kWouldBlock:
      return "would block";
    case CanStatus::kBusOff:
      return "bus-off";
    case CanStatus::kInvalidFrame:
      return "invalid frame";
    case CanStatus::kClosed:
      return "closed";
    case CanStatus::kIoError:
      return "i/o error";
  }
  return "unknown";
}

const char* to_string(CanBusState state) {
  switch (state) {
    case CanBusState::kErrorActive:
      return "error-active";
    case CanBusState::kErrorWarning:
      return "error-warning";
    case CanBusState::kErrorPassive:
      return "error-passive";
    case CanBusState::kBusOff:
      return "bus-off";
    case CanBusState::kDown:
      return "down";
  }
  return "unknown";
}

}  // namespace teleop::can
