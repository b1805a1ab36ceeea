#pragma once
// Every teleop topic on the bus as serialized samples: what `teleop record` and `teleop bridge`
// both listen with. The tap joins the domain, subscribes to topics (the fixed ones of topics.h at
// once, or whatever discovery finds written) and hands each sample over on a Fast DDS thread.

#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "teleop/tools/topic_tools.h"
#include "teleop/transport/raw_endpoint.h"
#include "teleop/transport/sample_types.h"

namespace teleop::tools {

class Bus;

/// A topic the tap subscribed to.
struct TappedTopic {
  std::string name;
  const transport::SampleType* type = nullptr;
  transport::QosPreset qos = transport::QosPreset::kStream;
};

class BusTap {
 public:
  /// Called on the subscribing thread before the topic's first sample; returns the id its samples
  /// are handed over with.
  using OnTopic = std::function<int(const TappedTopic&)>;
  /// Called on a Fast DDS thread for every sample: must not block (the bus's threads wait).
  using OnSample = std::function<void(int topic_id, const transport::RawSample&)>;

  /// Joins the domain as participant `name`; `topics` limits the tap to those (empty: every teleop
  /// topic). Throws ConfigError on a bad node config.
  BusTap(const BusOptions& options, const std::string& name, std::vector<std::string> topics, OnTopic on_topic,
         OnSample on_sample);
  ~BusTap();

  /// The fixed topics of topics.h, written or not (a node starting later loses no first sample).
  void subscribe_known_topics();
  /// Every teleop topic discovery has found a writer of that is not subscribed yet (the
  /// families: one topic per object, per contact pair). Call it again and again.
  void subscribe_new_topics();
  /// Leaves the bus: no sample arrives after it returns.
  void close();

  const std::set<std::string>& subscribed() const { return subscribed_; }
  int domain_id() const { return domain_id_; }

 private:
  bool wanted(const std::string& topic) const;
  void subscribe(const std::string& name, const transport::SampleType& type);

  std::vector<std::string> topics_;
  OnTopic on_topic_;
  OnSample on_sample_;
  std::set<std::string> subscribed_;
  int domain_id_ = 0;
  std::unique_ptr<Bus> bus_;
};

}  // namespace teleop::tools
