// The sample every variant sends, and its size on the wire.

#include <unistd.h>

#include <fastdds/rtps/common/SerializedPayload.h>

#include <cstdio>

#include "roundtrip.h"
#include "teleop/transport/joint_fields.h"
#include "teleop/transport/type_support.h"

namespace teleop::bench {

msg::JointState make_sample(const std::string& source, size_t joints) {
  msg::JointState s;
  s.header().source(source);
  s.robot("panda");
  s.arm("right");
  transport::presize_joint_state(s, joints);
  for (size_t i = 0; i < joints; ++i) {
    const double x = static_cast<double>(i + 1);
    s.q_rad()[i] = 0.1 * x;
    s.dq_radps()[i] = -0.01 * x;
    s.tau_measured_nm()[i] = 1.5 * x;
    s.tau_ext_nm()[i] = 0.05 * x;
  }
  return s;
}

std::vector<unsigned char> serialize(msg::JointState sample) {
  transport::PubSubTypeOf<msg::JointState>::type type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type.m_typeSize);
  if (!type.serialize(&sample, &payload)) throw std::runtime_error("could not serialize a JointState");
  return {payload.data, payload.data + payload.length};
}

uint32_t serialized_size_bound(msg::JointState sample) {
  transport::PubSubTypeOf<msg::JointState>::type type;
  return type.getSerializedSizeProvider(&sample)();
}

std::string session_source() {
  char buf[32];
  std::snprintf(buf, sizeof buf, "bench-%08x", static_cast<unsigned>(getpid()));
  return buf;
}

}  // namespace teleop::bench
