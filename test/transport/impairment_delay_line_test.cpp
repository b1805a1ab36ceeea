#include "teleop/transport/impairment/delay_line.h"

#include <gtest/gtest.h>

#include <chrono>
#include <mutex>
#include <thread>
#include <vector>

#include "teleop/common/clock.h"

namespace teleop::transport::impairment {
namespace {

namespace rtps = eprosima::fastrtps::rtps;

// a sender resource that records what it is asked to send, and when
class RecordingSender : public rtps::SenderResource {
 public:
  struct Sent {
    std::vector<uint8_t> bytes;
    uint32_t port;
    int64_t at_ns;
  };
  RecordingSender() : rtps::SenderResource(LOCATOR_KIND_UDPv4) {
    send_lambda_ = [this](const rtps::octet* data, uint32_t size, rtps::LocatorsIterator* begin,
                          rtps::LocatorsIterator* end, const std::chrono::steady_clock::time_point&) {
      std::lock_guard lock(mutex);
      for (auto& it = *begin; it != *end; ++it) sent.push_back({{data, data + size}, (*it).port, monotonic_now_ns()});
      return true;
    };
  }
  std::vector<Sent> snapshot() {
    std::lock_guard lock(mutex);
    return sent;
  }
  std::mutex mutex;
  std::vector<Sent> sent;
};

rtps::Locator_t port(uint32_t p) {
  rtps::Locator_t l;
  l.kind = LOCATOR_KIND_UDPv4;
  l.port = p;
  return l;
}

bool eventually(const std::function<bool()>& f) {
  for (int i = 0; i < 5000; ++i) {
    if (f()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return f();
}

TEST(DelayLine, SendsEachMessageAtItsDueTimeInDueOrder) {
  RecordingSender sender;
  DelayLine line(16, 64);
  const int64_t now = monotonic_now_ns();
  const uint8_t a[] = {1}, b[] = {2}, c[] = {3};
  // pushed out of order; equal due times keep their push order
  ASSERT_TRUE(line.push(now + 30 * kNsPerMs, &sender, port(3), c, 1));
  ASSERT_TRUE(line.push(now + 10 * kNsPerMs, &sender, port(1), a, 1));
  ASSERT_TRUE(line.push(now + 10 * kNsPerMs, &sender, port(2), b, 1));
  ASSERT_TRUE(eventually([&] { return sender.snapshot().size() == 3; }));
  const auto sent = sender.snapshot();
  EXPECT_EQ(sent[0].bytes, std::vector<uint8_t>{1});
  EXPECT_EQ(sent[1].bytes, std::vector<uint8_t>{2});
  EXPECT_EQ(sent[2].bytes, std::vector<uint8_t>{3});
  EXPECT_EQ(sent[2].port, 3u);
  // never early (how late is measured by the benchmark, not asserted here)
  EXPECT_GE(sent[0].at_ns, now + 10 * kNsPerMs);
  EXPECT_GE(sent[2].at_ns, now + 30 * kNsPerMs);
  EXPECT_EQ(line.sent(), 3u);
}

TEST(DelayLine, CopiesTheMessageSoTheCallerMayReuseItsBuffer) {
  RecordingSender sender;
  DelayLine line(4, 64);
  uint8_t buffer[] = {7, 7, 7};
  ASSERT_TRUE(line.push(monotonic_now_ns() + 5 * kNsPerMs, &sender, port(1), buffer, 3));
  buffer[0] = 0;  // the transport's buffer is reused at once
  ASSERT_TRUE(eventually([&] { return sender.snapshot().size() == 1; }));
  EXPECT_EQ(sender.snapshot()[0].bytes, (std::vector<uint8_t>{7, 7, 7}));
}

TEST(DelayLine, RefusesAndCountsWhenFullOrTooLarge) {
  RecordingSender sender;
  DelayLine line(2, 8);
  const uint8_t m[16] = {};
  const int64_t later = monotonic_now_ns() + kNsPerS;
  EXPECT_TRUE(line.push(later, &sender, port(1), m, 8));
  EXPECT_FALSE(line.push(later, &sender, port(1), m, 16)) << "larger than a slot";
  EXPECT_TRUE(line.push(later, &sender, port(1), m, 8));
  EXPECT_FALSE(line.push(later, &sender, port(1), m, 8)) << "no slot left";
  EXPECT_EQ(line.dropped_full(), 2u);
}

TEST(DelayLine, StopDropsWhatIsStillWaitingAndCountsIt) {
  RecordingSender sender;
  DelayLine line(8, 8);
  const uint8_t m[1] = {};
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(line.push(monotonic_now_ns() + 10 * kNsPerS, &sender, port(1), m, 1));
  line.stop();
  EXPECT_EQ(line.dropped_at_stop(), 5u);
  EXPECT_TRUE(sender.snapshot().empty());
  EXPECT_FALSE(line.push(monotonic_now_ns(), &sender, port(1), m, 1)) << "a stopped line takes nothing";
  line.stop();  // idempotent
}

}  // namespace
}  // namespace teleop::transport::impairment
