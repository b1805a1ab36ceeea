#pragma once
// Versions of the bag layout (docs/recording.md).

namespace teleop::bag {

/// The newest teleop_bag.format_version this library reads; the one it writes.
constexpr int kBagFormatVersion = 1;
/// The newest rosbag2 metadata.yaml version this library reads; the one it writes (ROS 2 Humble's).
constexpr int kRosbag2MetadataVersion = 5;

}  // namespace teleop::bag
