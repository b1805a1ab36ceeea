#pragma once
// A teleop sample as the serialized bytes a DDS reader hands the tools, and its catalogue entry:
// what the tools' units feed sample_text() and recordings.

#include <gtest/gtest.h>

#include <fastdds/rtps/common/SerializedPayload.h>

#include <cstdint>
#include <vector>

#include "teleop/transport/sample_types.h"
#include "teleop/transport/type_support.h"

namespace teleop::tools {

template <typename T>
std::vector<uint8_t> serialize(T sample) {
  typename transport::PubSubTypeOf<T>::type support;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(support.m_typeSize);
  EXPECT_TRUE(support.serialize(&sample, &payload));
  return {payload.data, payload.data + payload.length};
}

template <typename T>
const transport::SampleType& type_of() {
  return *transport::find_sample_type(typename transport::PubSubTypeOf<T>::type().getName());
}

}  // namespace teleop::tools
