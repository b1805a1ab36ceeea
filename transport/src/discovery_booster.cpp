#include "discovery_booster.h"

#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>

#include <chrono>
#include <vector>

#include "teleop/common/clock.h"

namespace teleop::transport {

namespace dds = eprosima::fastdds::dds;

DiscoveryBooster::DiscoveryBooster(dds::Publisher& publisher, dds::Subscriber& subscriber, DiscoveryBoost boost)
    : publisher_(publisher), subscriber_(subscriber), boost_(boost), thread_([this] { run(); }) {}

DiscoveryBooster::~DiscoveryBooster() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void DiscoveryBooster::kick() {
  if (boost_.duration_ns <= 0) return;
  {
    std::lock_guard lock(mutex_);
    if (!armed_) return;
    boost_until_ns_ = monotonic_now_ns() + boost_.duration_ns;
  }
  wake_.notify_all();
}

void DiscoveryBooster::arm_and_kick() {
  {
    std::lock_guard lock(mutex_);
    armed_ = true;
  }
  kick();
}

void DiscoveryBooster::run() {
  std::unique_lock lock(mutex_);
  while (!stop_) {
    if (monotonic_now_ns() >= boost_until_ns_) {
      wake_.wait(lock, [&] { return stop_ || monotonic_now_ns() < boost_until_ns_; });
      continue;
    }
    lock.unlock();
    reannounce();
    lock.lock();
    wake_.wait_for(lock, std::chrono::nanoseconds(boost_.period_ns), [&] { return stop_; });
  }
}

namespace {

// a user data that differs from the last one: Fast DDS sends the endpoint's announcement afresh
template <typename Qos>
void bump(Qos& qos, uint32_t generation) {
  std::vector<eprosima::fastrtps::rtps::octet> data(4);
  for (int i = 0; i < 4; ++i) data[static_cast<size_t>(i)] = static_cast<uint8_t>(generation >> (8 * i));
  qos.user_data().data_vec(data);
}

}  // namespace

void DiscoveryBooster::reannounce() {
  ++generation_;
  std::vector<dds::DataWriter*> writers;
  std::vector<dds::DataReader*> readers;
  publisher_.get_datawriters(writers);
  subscriber_.get_datareaders(readers);
  for (dds::DataWriter* w : writers) {
    dds::DataWriterQos qos = w->get_qos();
    bump(qos, generation_);
    if (w->set_qos(qos) == eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
      announcements_.fetch_add(1, std::memory_order_relaxed);
    }
  }
  for (dds::DataReader* r : readers) {
    dds::DataReaderQos qos = r->get_qos();
    bump(qos, generation_);
    if (r->set_qos(qos) == eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
      announcements_.fetch_add(1, std::memory_order_relaxed);
    }
  }
}

}  // namespace teleop::transport
