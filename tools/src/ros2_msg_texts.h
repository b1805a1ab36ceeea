#pragma once
// The .msg files of idl/ros2/teleop_msgs, compiled in (tools/CMakeLists.txt generates their
// list): what an MCAP recording embeds as each channel's ros2msg schema.

#include <string_view>
#include <vector>

namespace teleop::tools {

struct Ros2MsgText {
  std::string_view name;  ///< "JointState"
  std::string_view text;  ///< the file's content
};

const std::vector<Ros2MsgText>& ros2_msg_texts();

}  // namespace teleop::tools
