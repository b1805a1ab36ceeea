#include "teleop/tools/message_schemas.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "ros2_msg_texts.h"

namespace teleop::tools {
namespace {

constexpr std::string_view kPackage = "teleop_msgs/";

std::string_view text_of(std::string_view name) {
  for (const Ros2MsgText& m : ros2_msg_texts()) {
    if (m.name == name) return m.text;
  }
  throw std::out_of_range("no message teleop_msgs/" + std::string(name) + " in idl/ros2/teleop_msgs/msg");
}

bool is_message(std::string_view name) {
  const auto& texts = ros2_msg_texts();
  return std::any_of(texts.begin(), texts.end(), [&](const Ros2MsgText& m) { return m.name == name; });
}

// the messages a .msg text's fields use: each line's first word without its array bounds and
// package ("Pose", "teleop_msgs/Pose[<=8]" -> "Pose"); comments and primitives are not messages
std::vector<std::string> used_messages(std::string_view text) {
  std::vector<std::string> used;
  std::istringstream lines{std::string(text)};
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line.substr(0, line.find('#')));
    std::string type;
    if (!(words >> type)) continue;
    type = type.substr(0, type.find('['));
    if (type.rfind(kPackage, 0) == 0) type = type.substr(kPackage.size());
    if (is_message(type)) used.push_back(type);
  }
  return used;
}

void add_dependencies(std::string_view message, std::vector<std::string>& order) {
  for (const std::string& used : used_messages(text_of(message))) {
    if (std::find(order.begin(), order.end(), used) != order.end()) continue;
    order.push_back(used);
    add_dependencies(used, order);
  }
}

// "teleop/msg/JointState" -> "JointState"
std::string short_name(const transport::SampleType& type) { return type.bag_name.substr(type.bag_name.rfind('/') + 1); }

}  // namespace

std::string ros2_msg_name(const transport::SampleType& type) { return std::string(kPackage) + "msg/" + short_name(type); }

std::string ros2_msg_schema(const std::string& message) {
  std::string schema(text_of(message));
  std::vector<std::string> order{message};
  add_dependencies(message, order);
  for (size_t i = 1; i < order.size(); ++i) {
    if (!schema.empty() && schema.back() != '\n') schema += '\n';
    schema += std::string(80, '=') + "\nMSG: " + std::string(kPackage) + order[i] + "\n" + std::string(text_of(order[i]));
  }
  return schema;
}

bag::TopicInfo recorded_topic(const std::string& name, const transport::SampleType& type, const std::string& qos,
                              RecordingFormat format) {
  bag::TopicInfo topic;
  topic.name = name;
  topic.qos_profile = qos;
  if (format == RecordingFormat::kSqlite3) {
    topic.type = type.bag_name;
    return topic;
  }
  topic.type = ros2_msg_name(type);
  topic.schema = ros2_msg_schema(short_name(type));
  topic.schema_encoding = "ros2msg";
  return topic;
}

bag::TopicInfo topic_for(const bag::TopicInfo& topic, RecordingFormat format) {
  const transport::SampleType* type = transport::find_sample_type(topic.type);
  if (type == nullptr) return topic;
  return recorded_topic(topic.name, *type, topic.qos_profile, format);
}

}  // namespace teleop::tools
