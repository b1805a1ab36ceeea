#include "ros2_robot_link.h"

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <cmath>
#include <stdexcept>

#include "geometry_msgs/msg/WrenchStamped_PubSubTypes.h"
#include "joint_name_map.h"
#include "sensor_msgs/msg/JointState_PubSubTypes.h"
#include "std_msgs/msg/Float64MultiArray_PubSubTypes.h"
#include "teleop/common/clock.h"

namespace teleop::robot {
namespace dds = eprosima::fastdds::dds;
using JointStateMsg = sensor_msgs::msg::dds_::JointState_;
using WrenchMsg = geometry_msgs::msg::dds_::WrenchStamped_;
using CommandMsg = std_msgs::msg::dds_::Float64MultiArray_;

namespace {

// ROS 2 puts topic /x on DDS topic rt/x
std::string dds_topic(const std::string& ros_topic) { return "rt" + ros_topic; }

bool all_finite(const std::vector<double>& values) {
  for (double v : values) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

// a reader that hands each valid sample to `on_sample` on Fast DDS's thread
template <typename Msg>
class TakingListener : public dds::DataReaderListener {
 public:
  template <typename F>
  explicit TakingListener(F on_sample) : on_sample_(std::move(on_sample)) {}
  void on_data_available(dds::DataReader* reader) override {
    dds::SampleInfo info;
    while (reader->take_next_sample(&sample_, &info) == eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
      if (info.valid_data) on_sample_(sample_);
    }
  }

 private:
  std::function<void(const Msg&)> on_sample_;
  Msg sample_;
};

}  // namespace

struct Ros2RobotLink::Endpoints {
  dds::DomainParticipant* participant = nullptr;
  dds::Publisher* publisher = nullptr;
  dds::Subscriber* subscriber = nullptr;
  dds::DataWriter* writer = nullptr;
  std::unique_ptr<TakingListener<JointStateMsg>> state_listener;
  std::unique_ptr<TakingListener<WrenchMsg>> wrench_listener;
  JointNameMap names;
  CommandMsg command;

  explicit Endpoints(const Ros2HardwareConfig& config) : names(config.joints, config.ignored_joints) {}

  dds::Topic* topic(const std::string& ros_topic, dds::TypeSupport type) {
    // type objects and type information stay out of discovery: Cyclone DDS (rmw_cyclonedds)
    // rejects Fast DDS 2.9's and ignores the endpoint (docs/transport.md)
    type->auto_fill_type_object(false);
    type->auto_fill_type_information(false);
    if (type.register_type(participant) != eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
      throw std::runtime_error("DDS refused the type " + type.get_type_name());
    }
    dds::Topic* t = participant->create_topic(dds_topic(ros_topic), type.get_type_name(), dds::TOPIC_QOS_DEFAULT);
    if (t == nullptr) throw std::runtime_error("DDS refused the topic " + ros_topic);
    return t;
  }

  void reader(const std::string& ros_topic, dds::TypeSupport type, dds::DataReaderListener* listener) {
    dds::DataReaderQos qos;  // the library's defaults, not a profile file's
    qos.reliability().kind = dds::BEST_EFFORT_RELIABILITY_QOS;
    qos.durability().kind = dds::VOLATILE_DURABILITY_QOS;
    qos.history().kind = dds::KEEP_LAST_HISTORY_QOS;
    qos.history().depth = 8;
    if (subscriber->create_datareader(topic(ros_topic, type), qos, listener) == nullptr) {
      throw std::runtime_error("DDS refused a reader of " + ros_topic);
    }
  }
};

Ros2RobotLink::Ros2RobotLink(const Ros2HardwareConfig& config)
    : config_(config), participant_(config.participant), dds_(std::make_unique<Endpoints>(config)) {
  dds_->participant = participant_.dds();
  dds_->publisher = dds_->participant->create_publisher(dds::PublisherQos());
  dds_->subscriber = dds_->participant->create_subscriber(dds::SubscriberQos());
  if (dds_->publisher == nullptr || dds_->subscriber == nullptr) throw std::runtime_error("DDS refused a publisher or subscriber");

  dds::DataWriterQos writer_qos;
  writer_qos.reliability().kind = dds::RELIABLE_RELIABILITY_QOS;
  writer_qos.reliability().max_blocking_time = {0, 100'000};
  writer_qos.durability().kind = dds::VOLATILE_DURABILITY_QOS;
  writer_qos.history().kind = dds::KEEP_LAST_HISTORY_QOS;
  writer_qos.history().depth = 1;
  writer_qos.publish_mode().kind = dds::SYNCHRONOUS_PUBLISH_MODE;
  dds_->writer = dds_->publisher->create_datawriter(
      dds_->topic(config.command_topic, dds::TypeSupport(new std_msgs::msg::dds_::Float64MultiArray_PubSubType())), writer_qos);
  if (dds_->writer == nullptr) throw std::runtime_error("DDS refused a writer of " + config.command_topic);
  dds_->command.data_().assign(config.joints.size(), 0.0);

  dds_->state_listener = std::make_unique<TakingListener<JointStateMsg>>([this](const JointStateMsg& s) { on_state(&s); });
  dds_->reader(config.state_topic, dds::TypeSupport(new sensor_msgs::msg::dds_::JointState_PubSubType()),
               dds_->state_listener.get());
  if (!config.wrench_topic.empty()) {
    dds_->wrench_listener = std::make_unique<TakingListener<WrenchMsg>>([this](const WrenchMsg& w) { on_wrench(&w); });
    dds_->reader(config.wrench_topic, dds::TypeSupport(new geometry_msgs::msg::dds_::WrenchStamped_PubSubType()),
                 dds_->wrench_listener.get());
  }
}

Ros2RobotLink::~Ros2RobotLink() {
  // the endpoints go before their listeners; the participant deletes the topics
  dds_->subscriber->delete_contained_entities();
  dds_->participant->delete_subscriber(dds_->subscriber);
  dds_->publisher->delete_contained_entities();
  dds_->participant->delete_publisher(dds_->publisher);
}

void Ros2RobotLink::on_state(const void* sample) {
  const auto& s = *static_cast<const JointStateMsg*>(sample);
  const size_t count = s.name_().size();
  const bool arrays = s.position_().size() == count && s.velocity_().size() == count &&
                      (s.effort_().empty() || s.effort_().size() == count);
  if (!dds_->names.map(s.name_()) || !arrays || !all_finite(s.position_()) || !all_finite(s.velocity_()) ||
      !all_finite(s.effort_())) {
    invalid_states_.fetch_add(1, std::memory_order_relaxed);
    std::lock_guard lock(mismatch_mutex_);
    if (mismatch_.empty()) {
      const std::string names = dds_->names.mismatch(s.name_());
      mismatch_ = !names.empty() ? names : !arrays ? "its position and velocity arrays do not match its names" : "a value is not finite";
    }
    return;
  }
  RobotStateRecord record;
  for (size_t i = 0; i < dds_->names.joints(); ++i) {
    const size_t k = dds_->names.index(i);
    record.q_rad[i] = s.position_()[k];
    record.dq_radps[i] = s.velocity_()[k];
    record.tau_nm[i] = s.effort_().empty() ? 0.0 : s.effort_()[k];
  }
  record.arrival_ns = monotonic_now_ns();
  record.stamp_ns = int64_t{s.header_().stamp_().sec_()} * 1'000'000'000 + s.header_().stamp_().nanosec_();
  states_.push(record);
}

void Ros2RobotLink::on_wrench(const void* sample) {
  const auto& stamped = *static_cast<const WrenchMsg*>(sample);
  if (!config_.wrench_frame.empty() && stamped.header_().frame_id_() != config_.wrench_frame) {
    invalid_wrenches_.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  const auto& w = stamped.wrench_();
  RobotWrenchRecord record{{w.force_().x_(), w.force_().y_(), w.force_().z_()},
                           {w.torque_().x_(), w.torque_().y_(), w.torque_().z_()},
                           monotonic_now_ns()};
  for (size_t i = 0; i < 3; ++i) {
    if (!std::isfinite(record.force_n[i]) || !std::isfinite(record.torque_nm[i])) {
      invalid_wrenches_.fetch_add(1, std::memory_order_relaxed);
      return;
    }
  }
  wrenches_.push(record);
}

bool Ros2RobotLink::newest_state(RobotStateRecord& out) {
  bool any = false;
  while (states_.pop(out)) any = true;
  return any;
}

bool Ros2RobotLink::newest_wrench(RobotWrenchRecord& out) {
  bool any = false;
  while (wrenches_.pop(out)) any = true;
  return any;
}

bool Ros2RobotLink::send(const JointVector& values) {
  std::vector<double>& data = dds_->command.data_();
  std::copy_n(values.begin(), data.size(), data.begin());
  return dds_->writer->write(&dds_->command);
}

void Ros2RobotLink::flush(double timeout_s) {
  const auto ns = static_cast<int64_t>(timeout_s * 1e9);
  (void)dds_->writer->wait_for_acknowledgments({static_cast<int32_t>(ns / 1'000'000'000), static_cast<uint32_t>(ns % 1'000'000'000)});
}

int Ros2RobotLink::command_readers() const {
  dds::PublicationMatchedStatus status;
  dds_->writer->get_publication_matched_status(status);
  return status.current_count;
}

std::string Ros2RobotLink::name_mismatch() const {
  std::lock_guard lock(mismatch_mutex_);
  return mismatch_;
}

}  // namespace teleop::robot
