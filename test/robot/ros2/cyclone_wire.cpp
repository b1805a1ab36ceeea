#include "cyclone_wire.h"

#include <dds/dds.h>
#include <dds/ddsi/ddsi_cdrstream.h>

#include "geometry_msgs/msg/WrenchStamped_.h"
#include "sensor_msgs/msg/JointState_.h"
#include "std_msgs/msg/Float64MultiArray_.h"

namespace teleop::robot::cyclone {
namespace {

// XCDR1, what Fast DDS 2.9 and ROS 2's RMWs write for final types
constexpr uint32_t kXcdr1 = 1;

std::vector<uint8_t> write(const void* sample, const dds_topic_descriptor_t& type) {
  dds_ostreamLE_t os;
  dds_ostream_init(&os.x, 0, kXcdr1);
  dds_stream_writeLE(&os, static_cast<const char*>(sample), type.m_ops);
  std::vector<uint8_t> bytes(os.x.m_buffer, os.x.m_buffer + os.x.m_index);
  dds_ostreamLE_fini(&os);
  return bytes;
}

// the sequences borrow the values' storage: Cyclone only reads them here
dds_sequence_double doubles(const std::vector<double>& v) {
  return {static_cast<uint32_t>(v.size()), static_cast<uint32_t>(v.size()), const_cast<double*>(v.data()), false};
}

std_msgs_msg_dds__Header_ header(const Stamp& s) {
  return {{s.sec, s.nanosec}, const_cast<char*>(s.frame_id.c_str())};
}

}  // namespace

std::vector<uint8_t> cdr(const JointStateValues& values) {
  std::vector<char*> names;
  for (const std::string& name : values.names) names.push_back(const_cast<char*>(name.c_str()));
  sensor_msgs_msg_dds__JointState_ s{};
  s.header_ = header(values.header);
  s.name_ = {static_cast<uint32_t>(names.size()), static_cast<uint32_t>(names.size()), names.data(), false};
  s.position_ = doubles(values.position);
  s.velocity_ = doubles(values.velocity);
  s.effort_ = doubles(values.effort);
  return write(&s, sensor_msgs_msg_dds__JointState__desc);
}

std::vector<uint8_t> cdr(const MultiArrayValues& values) {
  std::vector<std_msgs_msg_dds__MultiArrayDimension_> dims;
  for (const Dimension& d : values.dims) dims.push_back({const_cast<char*>(d.label.c_str()), d.size, d.stride});
  std_msgs_msg_dds__Float64MultiArray_ m{};
  m.layout_.dim_ = {static_cast<uint32_t>(dims.size()), static_cast<uint32_t>(dims.size()), dims.data(), false};
  m.layout_.data_offset_ = values.data_offset;
  m.data_ = doubles(values.data);
  return write(&m, std_msgs_msg_dds__Float64MultiArray__desc);
}

std::vector<uint8_t> cdr(const WrenchValues& values) {
  geometry_msgs_msg_dds__WrenchStamped_ w{};
  w.header_ = header(values.header);
  w.wrench_.force_ = {values.force[0], values.force[1], values.force[2]};
  w.wrench_.torque_ = {values.torque[0], values.torque[1], values.torque[2]};
  return write(&w, geometry_msgs_msg_dds__WrenchStamped__desc);
}

}  // namespace teleop::robot::cyclone
