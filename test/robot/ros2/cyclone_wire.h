#pragma once
// Cyclone DDS's serialization of the ROS 2 messages the `ros2` backend speaks (its idlc types of
// the IDL rosidl makes, its own CDR writer), from plain values: the wire test's independent side.
// A translation unit of its own: Cyclone's headers and fastddsgen's have the same names.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace teleop::robot::cyclone {

struct Stamp {
  int32_t sec = 0;
  uint32_t nanosec = 0;
  std::string frame_id;
};

struct JointStateValues {
  Stamp header;
  std::vector<std::string> names;
  std::vector<double> position;
  std::vector<double> velocity;
  std::vector<double> effort;
};

struct Dimension {
  std::string label;
  uint32_t size = 0;
  uint32_t stride = 0;
};

struct MultiArrayValues {
  std::vector<Dimension> dims;
  uint32_t data_offset = 0;
  std::vector<double> data;
};

struct WrenchValues {
  Stamp header;
  std::array<double, 3> force{};
  std::array<double, 3> torque{};
};

/// The little-endian XCDR1 body (no encapsulation header) Cyclone writes for each message.
std::vector<uint8_t> cdr(const JointStateValues& values);
std::vector<uint8_t> cdr(const MultiArrayValues& values);
std::vector<uint8_t> cdr(const WrenchValues& values);

}  // namespace teleop::robot::cyclone
