#include "teleop/tools/bus_tap.h"

#include <algorithm>

#include "bus.h"

namespace teleop::tools {

BusTap::BusTap(const BusOptions& options, const std::string& name, std::vector<std::string> topics, OnTopic on_topic,
               OnSample on_sample)
    : topics_(std::move(topics)),
      on_topic_(std::move(on_topic)),
      on_sample_(std::move(on_sample)),
      bus_(std::make_unique<Bus>(options, name)) {
  domain_id_ = bus_->domain_id();
}

BusTap::~BusTap() = default;

void BusTap::subscribe_known_topics() {
  if (!bus_) return;
  for (const transport::KnownTopic& k : transport::known_topics()) {
    if (wanted(k.name) && subscribed_.count(k.name) == 0) subscribe(k.name, *k.type);
  }
}

void BusTap::subscribe_new_topics() {
  if (!bus_) return;
  for (const TopicView& t : bus_->topics()) {
    if (t.writers.empty() || subscribed_.count(t.name) > 0 || !wanted(t.name)) continue;
    const transport::SampleType* type = t.types.size() == 1 ? transport::find_sample_type(t.types.front()) : nullptr;
    if (type != nullptr) subscribe(t.name, *type);  // not ours: nothing to decode it with
  }
}

void BusTap::close() { bus_.reset(); }

bool BusTap::wanted(const std::string& topic) const {
  return topics_.empty() || std::find(topics_.begin(), topics_.end(), topic) != topics_.end();
}

void BusTap::subscribe(const std::string& name, const transport::SampleType& type) {
  const transport::QosPreset qos = transport::topic_qos(name);
  const int id = on_topic_({name, &type, qos});
  bus_->participant().make_raw_reader(name, type, qos, [on_sample = &on_sample_, id](const transport::RawSample& s) {
    (*on_sample)(id, s);
  });
  subscribed_.insert(name);
}

}  // namespace teleop::tools
