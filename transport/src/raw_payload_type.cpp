#include "raw_payload_type.h"

#include <cstring>
#include <vector>

namespace teleop::transport {
namespace {

using Bytes = std::vector<uint8_t>;
using eprosima::fastrtps::rtps::SerializedPayload_t;

// the second byte of the encapsulation header says the byte order (RTPS 10.5)
constexpr uint16_t encapsulation_of(const Bytes& cdr) { return cdr.size() > 1 && cdr[1] == 0x01 ? CDR_LE : CDR_BE; }

}  // namespace

RawPayloadType::RawPayloadType(const SampleType& type) {
  setName(type.dds_name.c_str());
  m_typeSize = type.max_serialized_size;
  m_isGetKeyDefined = false;  // no teleop type has a key
}

bool RawPayloadType::serialize(void* data, SerializedPayload_t* payload) {
  const Bytes& cdr = *static_cast<const Bytes*>(data);
  if (cdr.size() > payload->max_size) return false;
  std::memcpy(payload->data, cdr.data(), cdr.size());
  payload->length = static_cast<uint32_t>(cdr.size());
  payload->encapsulation = encapsulation_of(cdr);
  return true;
}

bool RawPayloadType::deserialize(SerializedPayload_t* payload, void* data) {
  Bytes& cdr = *static_cast<Bytes*>(data);
  cdr.assign(payload->data, payload->data + payload->length);
  return true;
}

std::function<uint32_t()> RawPayloadType::getSerializedSizeProvider(void* data) {
  return [data] { return static_cast<uint32_t>(static_cast<const Bytes*>(data)->size()); };
}

void* RawPayloadType::createData() { return new Bytes(); }

void RawPayloadType::deleteData(void* data) { delete static_cast<Bytes*>(data); }

bool RawPayloadType::getKey(void*, eprosima::fastrtps::rtps::InstanceHandle_t*, bool) { return false; }

}  // namespace teleop::transport
