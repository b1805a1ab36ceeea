#include "teleop/transport/impairment/impairment_engine.h"
#include <algorithm>

#include "teleop/common/clock.h"
#include "rtps_classifier.h"

namespace teleop::transport::impairment {
namespace rtps = eprosima::fastrtps::rtps;

namespace {
// room for 35 ms of 1 kHz traffic on a dozen topics several times over; larger messages (big
// discovery packets) cannot be delayed and are counted as dropped
constexpr size_t kDelaySlots = 4096;
constexpr size_t kSlotBytes = 4096;
}  // namespace

ImpairmentEngine::ImpairmentEngine(const ImpairmentConfig& config, const std::string& self_name)
    : self_(self_name), seed_(config.seed), exclude_discovery_(config.exclude_discovery),
      delay_line_(kDelaySlots, kSlotBytes) {
  const int64_t start = monotonic_now_ns();
  std::vector<std::string> names;
  for (const auto& l : config.links) {
    // each link its own stream of decisions, reproducible from the run's seed
    const uint64_t link_seed = config.seed ^ hash_name((self_ + "->" + l.to).c_str());
    all_transparent_ = all_transparent_ && l.profile.is_transparent();
    auto link = std::make_unique<Link>(l.to, l.profile, link_seed, start);
    if (l.to == kAnyPeer) {
      any_peer_ = link.get();
    } else {
      names.push_back(l.to);
    }
    links_.push_back(std::move(link));
  }
  // peer indices follow the order of the named links; the "*" link (if any) is kept apart
  std::stable_partition(links_.begin(), links_.end(), [](const auto& l) { return l->to != kAnyPeer; });
  peers_.set_peer_names(names);
}

ImpairmentEngine::~ImpairmentEngine() { shutdown(); }

ImpairmentEngine::Link* ImpairmentEngine::link_for(const rtps::Locator_t& destination) {
  const int peer = peers_.lookup(destination);
  return peer >= 0 ? links_[static_cast<size_t>(peer)].get() : any_peer_;
}

bool ImpairmentEngine::send(rtps::SenderResource* low, const uint8_t* data, uint32_t size,
                            eprosima::fastdds::rtps::LocatorsIterator* begin, eprosima::fastdds::rtps::LocatorsIterator* end,
                            const std::chrono::steady_clock::time_point& timeout) {
  if (all_transparent_) {
    passed_through_.fetch_add(1, std::memory_order_relaxed);
    return low->send(data, size, begin, end, timeout);
  }
  const bool pass_through = !active_.load(std::memory_order_acquire) ||
                            (exclude_discovery_ && is_discovery_message(data, size));
  const int64_t now = monotonic_now_ns();
  bool ok = true;
  // one decision per destination: each is its own link
  for (eprosima::fastdds::rtps::LocatorsIterator& it = *begin; it != *end; ++it) {
    const rtps::Locator_t& destination = *it;
    Link* link = pass_through ? nullptr : link_for(destination);
    if (link == nullptr) {
      ok = send_to_one(low, data, size, destination) && ok;
      continue;
    }
    Decision d;
    {
      std::lock_guard lock(link->mutex);
      d = link->model.decide(now, size);
    }
    for (int copy = 0; copy < d.copies; ++copy) {
      const int64_t due = d.deliver_at_ns[static_cast<size_t>(copy)];
      if (due <= now) {
        ok = send_to_one(low, data, size, destination) && ok;
      } else {
        delay_line_.push(due, low, destination, data, size);
      }
    }
  }
  // a dropped message is a successful send as far as the sender can tell, as on a real network
  return ok;
}

void ImpairmentEngine::shutdown() {
  active_.store(false, std::memory_order_release);
  delay_line_.stop();
}

std::vector<LinkReport> ImpairmentEngine::reports() const {
  std::vector<LinkReport> out;
  for (const auto& l : links_) {
    std::lock_guard lock(l->mutex);
    const LinkPhase& first = l->model.profile().phases.front();
    out.push_back({self_, l->to, l->model.profile().name, l->model.stats(), first.loss.expected_loss_rate(),
                   first.delay_ns});
  }
  return out;
}

size_t ImpairmentEngine::snapshot(Snapshot* out, size_t capacity) const {
  size_t n = 0;
  for (const auto& l : links_) {
    if (n == capacity) break;
    std::lock_guard lock(l->mutex);
    out[n++] = Snapshot{&l->to, &l->model.profile().name, l->model.stats()};
  }
  return n;
}

}  // namespace teleop::transport::impairment
