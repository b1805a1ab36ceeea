#pragma once
// Topic names of one arm of a multi-arm robot: each arm of a two-arm leader station, follower or
// twin has its own command, state, wrench and energy topics, named by appending the arm's name
// ("teleop/leader/joint_command/left"). The unnamed arm (a one-arm robot) keeps the plain names,
// so one-arm setups are unchanged. Separate topics rather than one keyed topic: each arm's link
// is impaired, watched for liveliness and reported on its own.

#include <string>

#include "teleop/transport/topics.h"

namespace teleop::transport {

template <typename T>
class ArmTopic {
 public:
  /// `arm` "" gives `topic` itself.
  ArmTopic(const TopicSpec<T>& topic, const std::string& arm)
      : name_(arm.empty() ? std::string(topic.name) : std::string(topic.name) + "/" + arm),
        spec_{name_.c_str(), topic.qos} {}
  // the spec points into name_: neither may be copied apart
  ArmTopic(const ArmTopic&) = delete;
  ArmTopic& operator=(const ArmTopic&) = delete;

  /// For Publication / Subscription constructors, which copy the name: use within the expression.
  operator const TopicSpec<T>&() const { return spec_; }
  const std::string& name() const { return name_; }

 private:
  std::string name_;
  TopicSpec<T> spec_;
};

/// The arm's topic for `topic`: `Publication pub(participant, arm_topic(topics::kFollowerState, "left"), ...)`.
template <typename T>
ArmTopic<T> arm_topic(const TopicSpec<T>& topic, const std::string& arm) {
  return ArmTopic<T>(topic, arm);
}

/// The value of a sample's `arm` field for `arm` ("single" for the unnamed arm of a one-arm robot).
inline const char* arm_label(const std::string& arm) { return arm.empty() ? "single" : arm.c_str(); }

}  // namespace teleop::transport
