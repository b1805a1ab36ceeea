#pragma once
// A reader plus reception statistics: the loop calls `poll()` once per cycle to drain what
// arrived, and reads the newest sample with `latest()`. The stream follows one writer at a time
// (common/stream_session.h): a restarted peer is followed from its first sample, another writer
// is refused while the followed one talks, and no sequence number can hold the stream. A
// subscription may also accept only the samples of named nodes (`accept_only`): a name keeps two
// labs apart on one domain, though only DDS Security's permissions authenticate a writer.
//
// What the flow follows and refuses is published in the node's status (FlowStatus), and the first
// refusal of each kind per writer, like each change of the followed writer, is an event for the
// node's log (common/node_event.h).

#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <teleop/msg/status.h>

#include "teleop/common/clock.h"
#include "teleop/common/clock_offset.h"
#include "teleop/common/fixed_text.h"
#include "teleop/common/node_event.h"
#include "teleop/common/refusal_memory.h"
#include "teleop/common/sequence_tracker.h"
#include "teleop/common/stream_session.h"
#include "teleop/transport/participant.h"

namespace teleop::transport {

template <typename T>
class Subscription {
 public:
  /// Setup time: creates the reader. `policy` says when another writer may take the stream over.
  /// The node needs a writer on the topic (it is awaited, see mark_optional()).
  Subscription(Participant& participant, const TopicSpec<T>& topic, StreamSessionPolicy policy = {})
      : topic_name_(topic.name), reader_(participant.make_reader(topic)), session_(policy), events_(&participant.events()) {
    reader_.set_awaited(true);
  }

  /// The node works without a writer on this topic (an alternative or optional input): nobody
  /// is told it waits for one. Setup time.
  void mark_optional() { reader_.set_awaited(false); }

  /// Takes only the samples of these nodes (SampleHeader.source); empty: of any node. Setup time.
  void accept_only(const std::vector<std::string>& nodes) {
    accepted_.clear();
    for (const std::string& n : nodes) accepted_.emplace_back().assign(n);
  }

  /// Takes every sample that arrived since the last poll, updates the statistics and keeps the
  /// newest of the followed writer as `latest()`. Non-blocking and real-time safe. Returns the
  /// number of samples that became the newest (0: `latest()` is unchanged).
  int poll() {
    const int64_t now_mono_ns = monotonic_now_ns();
    // DDS stamps a reception on CLOCK_REALTIME: moved onto the monotonic clock once per poll
    real_to_mono_ns_ = now_mono_ns - system_now_ns();
    session_.begin_poll(now_mono_ns);
    int newest = 0;
    int64_t reception_ns = 0;
    while (reader_.take_next(incoming_, reception_ns, writer_)) newest += take(reception_ns, now_mono_ns);
    if (candidate_pending_) newest += settle_candidate(now_mono_ns);
    // what the loop works with: how old the newest sample is now
    if (has_sample_) age_.record(system_now_ns() - latest_.header().stamp_ns());
    reader_.report_flow(tracker_.received(), tracker_.lost(), latency_smoothed_ns_, clock_offset_.estimate_ns());
    FlowAuthority& a = reader_.authority();
    a.refused[msg::REFUSAL_OTHER_WRITER] = session_.refused_other_writer();
    a.refused[msg::REFUSAL_SEQUENCE_JUMP] = session_.refused_sequence_jump();
    return newest;
  }

  /// The node found the newest sample invalid (`reason`: a short name such as "wrong_size"; `code`
  /// < 24 tells reasons apart in the log's memory): it is not in force. Real-time safe.
  void reject_latest(uint32_t code, std::string_view reason) {
    FlowAuthority& a = reader_.authority();
    a.in_force = false;
    ++a.refused[msg::REFUSAL_INVALID];
    note_refusal(latest_writer_, latest_.header().source(), msg::REFUSAL_INVALID, 8 + code, reason,
                 monotonic_now_ns());
  }

  /// Blocks until a sample is waiting to be polled or `timeout_ns` passed (lock-step exchanges only).
  bool wait_for_data(int64_t timeout_ns) { return reader_.wait_for_data(timeout_ns); }

  bool has_sample() const { return has_sample_; }
  /// The newest sample received so far (valid when has_sample()).
  const T& latest() const { return latest_; }
  /// Time since the newest sample arrived, on the monotonic clock; huge when none arrived.
  int64_t age_ns(int64_t now_mono_ns) const {
    return has_sample_ ? now_mono_ns - latest_receive_mono_ns_ : INT64_MAX;
  }

  const std::string& topic_name() const { return topic_name_; }
  const SequenceTracker& stats() const { return tracker_; }
  /// The followed writer's session (0 before the first sample) and what was refused.
  const StreamSession& session() const { return session_; }
  /// Samples refused because their node is not accepted (accept_only).
  uint64_t refused_not_accepted() const { return reader_.authority().refused[msg::REFUSAL_NOT_ACCEPTED]; }
  /// Newest samples the node found invalid (reject_latest).
  uint64_t rejected() const { return reader_.authority().refused[msg::REFUSAL_INVALID]; }
  /// Age of the newest sample at each poll (source stamp to now, CLOCK_REALTIME).
  const DurationHistogram& age() const { return age_; }
  /// The followed node's clock against ours, from its samples (common/clock_offset.h): subtract
  /// it from a sample's age on our clock for its delay beyond the writer's fastest sample [ns].
  /// Kept over the sessions of one node (a restarted leader), learnt afresh for another node.
  int64_t clock_offset_ns() const { return clock_offset_.estimate_ns(); }
  /// The largest |clock_offset_ns()| seen over the run [ns].
  int64_t clock_offset_max_ns() const { return clock_offset_max_ns_; }
  const Reader<T>& reader() const { return reader_; }

 private:
  // one drained sample (in incoming_): 1 when it became the newest
  int take(int64_t reception_ns, int64_t now_mono_ns) {
    const auto& header = incoming_.header();
    if (!accepts(header.source())) {
      ++reader_.authority().refused[msg::REFUSAL_NOT_ACCEPTED];
      note_refusal(writer_, header.source(), msg::REFUSAL_NOT_ACCEPTED, msg::REFUSAL_NOT_ACCEPTED, {}, now_mono_ns);
      return 0;
    }
    const int64_t arrival_ns = std::min(reception_ns + real_to_mono_ns_, now_mono_ns);
    switch (session_.admit(writer_, header.seq(), arrival_ns)) {
      case Admission::kOtherWriter:
        note_refusal(writer_, header.source(), msg::REFUSAL_OTHER_WRITER, msg::REFUSAL_OTHER_WRITER, {}, now_mono_ns);
        return 0;
      case Admission::kSequenceJump:
        note_refusal(writer_, header.source(), msg::REFUSAL_SEQUENCE_JUMP, msg::REFUSAL_SEQUENCE_JUMP, {}, now_mono_ns);
        return 0;
      case Admission::kCandidate:
        // kept aside: it takes over at the end of the poll unless the followed writer turns up
        std::swap(candidate_, incoming_);
        candidate_writer_ = writer_;
        candidate_reception_ns_ = reception_ns;
        candidate_pending_ = true;
        return 0;
      case Admission::kNewSession:
        begin_session(writer_, header.source(), now_mono_ns);
        return make_newest(incoming_, reception_ns, now_mono_ns);
      case Admission::kNewest: return make_newest(incoming_, reception_ns, now_mono_ns);
      case Admission::kOlder: record(header, reception_ns); return 0;
    }
    return 0;
  }

  // the end of a poll with a candidate: 1 when it took the stream over
  int settle_candidate(int64_t now_mono_ns) {
    candidate_pending_ = false;
    if (!session_.end_poll()) {
      note_refusal(candidate_writer_, candidate_.header().source(), msg::REFUSAL_OTHER_WRITER, msg::REFUSAL_OTHER_WRITER,
                   {}, now_mono_ns);
      return 0;
    }
    begin_session(candidate_writer_, candidate_.header().source(), now_mono_ns);
    return make_newest(candidate_, candidate_reception_ns_, now_mono_ns);
  }

  int make_newest(T& sample, int64_t reception_ns, int64_t now_mono_ns) {
    record(sample.header(), reception_ns);
    watch_clock(reception_ns - sample.header().stamp_ns(), sample.header().source(), now_mono_ns);
    // swap, not copy: both buffers keep their capacity, nothing is allocated
    std::swap(latest_, sample);
    has_sample_ = true;
    latest_receive_mono_ns_ = now_mono_ns;
    reader_.authority().in_force = true;
    return 1;
  }

  void record(const msg::SampleHeader& header, int64_t reception_ns) {
    // latency of the transport itself: source stamp to DDS reception, not to this poll
    tracker_.on_sample(header.seq(), header.stamp_ns(), reception_ns);
    smooth_latency(reception_ns - header.stamp_ns());
  }

  // the followed writer's clock: an estimate far from ours is said once per writer
  void watch_clock(int64_t apparent_ns, const msg::Name& source, int64_t now_mono_ns) {
    clock_offset_.add(apparent_ns, now_mono_ns);
    const int64_t offset_ns = clock_offset_.estimate_ns();
    clock_offset_max_ns_ = std::max(clock_offset_max_ns_, offset_ns < 0 ? -offset_ns : offset_ns);
    if (clock_offset_said_ || (offset_ns < kClockOffsetWarnNs && offset_ns > -kClockOffsetWarnNs)) return;
    clock_offset_said_ = true;
    NodeEvent e;
    e.kind = NodeEvent::Kind::kClockOffset;
    e.mono_ns = now_mono_ns;
    e.value = static_cast<double>(offset_ns) * 1e-9;
    e.topic.assign(topic_name_);
    e.who.assign(std::string_view(source.c_str(), source.size()));
    events_->push(e);
  }

  void begin_session(const WriterId& writer, const msg::Name& source, int64_t now_mono_ns) {
    tracker_.begin_session();
    // the clock is the node's: a restarted writer of the same node keeps it (and its first command
    // is judged against what its predecessor's samples taught), another node may run elsewhere
    if (!(reader_.authority().following == std::string_view(source.c_str(), source.size()))) {
      clock_offset_.reset();
      clock_offset_said_ = false;
    }
    latest_writer_ = writer;
    reader_.authority().following.assign(std::string_view(source.c_str(), source.size()));
    reader_.authority().following_writer.assign(writer.hex().data());
    NodeEvent e;
    e.kind = NodeEvent::Kind::kFollowing;
    e.mono_ns = now_mono_ns;
    e.count = session_.session();
    e.topic.assign(topic_name_);
    e.who = reader_.authority().following;
    events_->push(e);
  }

  bool accepts(const msg::Name& source) const {
    if (accepted_.empty()) return true;
    const std::string_view s(source.c_str(), source.size());
    return std::any_of(accepted_.begin(), accepted_.end(), [&](const FixedText<32>& a) { return a == s; });
  }

  // the flow's last refusal; the first of each kind per writer goes to the node's log
  void note_refusal(const WriterId& writer, const msg::Name& source, uint32_t refusal, uint32_t kind,
                    std::string_view detail, int64_t now_mono_ns) {
    FlowAuthority& a = reader_.authority();
    a.refused_source.assign(std::string_view(source.c_str(), source.size()));
    a.refusal = refusal;
    a.refusal_detail.assign(detail);
    if (!refusals_.first(writer, kind, now_mono_ns)) return;
    NodeEvent e;
    e.kind = NodeEvent::Kind::kRefused;
    e.mono_ns = now_mono_ns;
    e.code = static_cast<int32_t>(refusal);
    e.topic.assign(topic_name_);
    e.who = a.refused_source;
    // the node's reason, or whom the flow follows instead
    e.detail = refusal == msg::REFUSAL_INVALID ? a.refusal_detail : a.following;
    e.count = session_.session();
    events_->push(e);
  }

  // an exponential average over ~64 samples: what NodeStatus shows as the flow's latency now
  void smooth_latency(int64_t latency_ns) {
    latency_smoothed_ns_ = tracker_.received() == 1 ? latency_ns : latency_smoothed_ns_ + (latency_ns - latency_smoothed_ns_) / 64;
  }

  // beyond this the two clocks (or the fastest path between them) are worth a line in the log
  static constexpr int64_t kClockOffsetWarnNs = 10'000'000;

  std::string topic_name_;
  Reader<T> reader_;
  ClockOffsetEstimate clock_offset_;
  int64_t clock_offset_max_ns_ = 0;
  bool clock_offset_said_ = false;
  StreamSession session_;
  NodeEventQueue* events_;
  std::vector<FixedText<32>> accepted_;
  RefusalMemory refusals_;
  WriterId writer_;
  WriterId latest_writer_;
  T incoming_;
  T latest_;
  T candidate_;
  WriterId candidate_writer_;
  int64_t candidate_reception_ns_ = 0;
  bool candidate_pending_ = false;
  int64_t real_to_mono_ns_ = 0;
  bool has_sample_ = false;
  int64_t latest_receive_mono_ns_ = 0;
  SequenceTracker tracker_;
  DurationHistogram age_;
  int64_t latency_smoothed_ns_ = 0;
};

}  // namespace teleop::transport
