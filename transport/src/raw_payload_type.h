#pragma once
// A DDS type that carries a sample's serialized bytes unchanged (a std::vector<uint8_t>) under the
// name of a teleop type: DDS matches types by name, so a raw reader receives what a typed writer
// sends and a raw writer is read by typed readers, with no (de)serialization in between.

#include <fastdds/dds/topic/TopicDataType.hpp>

#include "teleop/transport/sample_types.h"

namespace teleop::transport {

class RawPayloadType : public eprosima::fastdds::dds::TopicDataType {
 public:
  explicit RawPayloadType(const SampleType& type);

  bool serialize(void* data, eprosima::fastrtps::rtps::SerializedPayload_t* payload) override;
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override;
  std::function<uint32_t()> getSerializedSizeProvider(void* data) override;
  void* createData() override;
  void deleteData(void* data) override;
  bool getKey(void* data, eprosima::fastrtps::rtps::InstanceHandle_t* handle, bool force_md5) override;
};

}  // namespace teleop::transport
