#pragma once
// Bare Fast DDS, the floor the teleop transport is measured against: no teleop code, only the
// generated JointState type. The default participant with the UDPv4 transport only, writers
// best effort keep-last 1, readers best effort keep-last 16, data sharing off (default QoS
// otherwise); every received sample is handed over in the reader's listener, on the receive
// thread.

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <teleop/msg/arm.h>

namespace teleop::bench {

class BareDds {
 public:
  /// Receives topic index and sample on the Fast DDS receive thread; may modify the sample.
  using OnSample = std::function<void(int topic, msg::JointState& sample)>;

  /// Writers on `write_topics`, readers on `read_topics` (index i calls on_sample with i).
  BareDds(int domain, const std::vector<std::string>& write_topics, const std::vector<std::string>& read_topics,
          OnSample on_sample);
  ~BareDds();
  BareDds(const BareDds&) = delete;
  BareDds& operator=(const BareDds&) = delete;

  /// Writes on writer `topic`; false if DDS refused the sample.
  bool write(int topic, msg::JointState& sample);

  /// Every writer and every reader matched at least one remote endpoint.
  bool all_matched() const;

 private:
  struct ReaderListener;

  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  std::vector<eprosima::fastdds::dds::DataWriter*> writers_;
  std::vector<eprosima::fastdds::dds::DataReader*> readers_;
  std::vector<std::unique_ptr<ReaderListener>> listeners_;
};

}  // namespace teleop::bench
