#pragma once
// A sample of type T from the serialized bytes a DDS reader received (encapsulation first), for
// the tools that read recordings and raw subscriptions.

#include <fastdds/rtps/common/SerializedPayload.h>

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "teleop/transport/type_support.h"

namespace teleop::tools {

/// Throws std::runtime_error when the bytes hold no sample of T.
template <typename T>
T deserialized(const std::vector<uint8_t>& cdr) {
  typename transport::PubSubTypeOf<T>::type support;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<uint32_t>(cdr.size()));
  std::memcpy(payload.data, cdr.data(), cdr.size());
  payload.length = static_cast<uint32_t>(cdr.size());
  T sample;
  bool ok = false;
  try {
    ok = support.deserialize(&payload, &sample);
  } catch (const std::exception&) {
    ok = false;  // fastcdr throws on a buffer too short for what it reads
  }
  if (!ok) throw std::runtime_error("the bytes do not hold a " + std::string(support.getName()));
  return sample;
}

}  // namespace teleop::tools
