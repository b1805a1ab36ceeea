// write_sample_mcap FILE [COMPRESSION]: an MCAP recording, as `teleop record` writes it, of three
// samples of every teleop type (header and some fields set), for the interop test that reads it
// with the MCAP project's own reader (test/bag/mcap_interop/read_mcap.mjs).
#include <fastdds/rtps/common/SerializedPayload.h>

#include <cstdio>
#include <string>

#include "teleop/bag/mcap_writer.h"
#include "teleop/tools/message_schemas.h"
#include "teleop/transport/type_support.h"

namespace {

using namespace teleop;

template <typename T>
void add_samples(bag::McapWriter& writer, T sample) {
  typename transport::PubSubTypeOf<T>::type support;
  const transport::SampleType& type = *transport::find_sample_type(support.getName());
  const int topic = writer.add_topic(
      tools::recorded_topic("teleop/sample/" + type.bag_name, type, "", tools::RecordingFormat::kMcap));
  for (uint64_t seq = 1; seq <= 3; ++seq) {
    sample.header().seq(seq);
    sample.header().stamp_ns(1'700'000'000'000'000'000 + static_cast<int64_t>(seq) * 1'000'000);
    sample.header().source("write_sample_mcap");
    eprosima::fastrtps::rtps::SerializedPayload_t payload(support.m_typeSize);
    if (!support.serialize(&sample, &payload)) throw std::runtime_error("cannot serialize " + type.dds_name);
    const int64_t stamp = sample.header().stamp_ns();
    writer.write({topic, stamp + 500, 0, stamp, {}, payload.data, payload.length});
  }
}

msg::JointState joint_state() {
  msg::JointState s;
  s.robot("panda");
  s.arm("right");
  s.q_rad({0.5, -1.25, 2.0});
  s.tau_ext_nm({0.1});
  return s;
}

// with values, so that a figure of them (`teleop plot` of a recording) shows lines
msg::WrenchStamped wrench() {
  msg::WrenchStamped w;
  w.force_n().z(-12.5);
  w.torque_nm().x(0.25);
  return w;
}

msg::JointTorque joint_torque() {
  msg::JointTorque t;
  t.tau_nm({1.5, 0.5, -0.5});
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: write_sample_mcap FILE [zstd|lz4|none]\n");
    return 2;
  }
  const std::string compression = argc > 2 ? argv[2] : "zstd";
  bag::McapWriterOptions options{argv[1]};
  options.compression = compression == "lz4"    ? bag::McapCompression::kLz4
                        : compression == "none" ? bag::McapCompression::kNone
                                                : bag::McapCompression::kZstd;
  bag::McapWriter writer(options);
  add_samples(writer, joint_state());
  add_samples(writer, msg::JointCommand());
  add_samples(writer, msg::CartesianCommand());
  add_samples(writer, wrench());
  add_samples(writer, joint_torque());
  add_samples(writer, msg::HandCommand());
  add_samples(writer, msg::HandState());
  add_samples(writer, msg::NodeStatus());
  add_samples(writer, msg::ResetRequest());
  add_samples(writer, msg::TdpaEnergy());
  add_samples(writer, msg::GeomDistances());
  add_samples(writer, msg::ObjectPose());
  add_samples(writer, msg::EmergencyStop());
  writer.close();
  std::printf("wrote %s\n", argv[1]);
  return 0;
}
