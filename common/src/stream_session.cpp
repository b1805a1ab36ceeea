#include "teleop/common/stream_session.h"

#include <algorithm>

namespace teleop {

void StreamSession::begin_poll(int64_t now_mono_ns) {
  // a gap between polls longer than half the silence: we were not listening (a stall), so the
  // followed writer's silence is counted again from now
  if (!polled_ || now_mono_ns - last_poll_ns_ > policy_.takeover_silence_ns / 2) {
    listening_since_ns_ = now_mono_ns;
  }
  polled_ = true;
  last_poll_ns_ = now_mono_ns;
  followed_in_poll_ = false;
  candidate_ = Candidate{};
}

bool StreamSession::gone_at(int64_t t) const {
  return t - std::max(last_newest_ns_, listening_since_ns_) >= policy_.takeover_silence_ns;
}

void StreamSession::open(const WriterId& writer, uint64_t seq, int64_t arrival_ns) {
  ++session_;
  writer_ = writer;
  last_seq_ = seq;
  last_newest_ns_ = arrival_ns;
}

Admission StreamSession::admit(const WriterId& writer, uint64_t seq, int64_t arrival_mono_ns) {
  if (session_ == 0) {
    open(writer, seq, arrival_mono_ns);
    followed_in_poll_ = true;
    return Admission::kNewSession;
  }
  if (writer == writer_) return admit_followed(seq, arrival_mono_ns);
  return admit_other(writer, seq, arrival_mono_ns);
}

Admission StreamSession::admit_followed(uint64_t seq, int64_t arrival_ns) {
  followed_in_poll_ = true;
  const bool gone = gone_at(arrival_ns);
  if (seq > last_seq_) {
    if (seq - last_seq_ > policy_.max_sequence_jump && !gone) {
      ++refused_sequence_jump_;
      return Admission::kSequenceJump;
    }
    last_seq_ = seq;
    last_newest_ns_ = arrival_ns;
    return Admission::kNewest;
  }
  // a writer never numbers backwards: one that does after going quiet started afresh (or was
  // forged high before), and following it again is what keeps the stream from locking
  if (seq < last_seq_ && gone) {
    open(writer_, seq, arrival_ns);
    return Admission::kNewSession;
  }
  return Admission::kOlder;
}

Admission StreamSession::admit_other(const WriterId& writer, uint64_t seq, int64_t arrival_ns) {
  // one candidate per poll: the first writer heard after the followed one went quiet
  const bool may_take_over = candidate_.present ? writer == candidate_.writer : gone_at(arrival_ns);
  if (!may_take_over) {
    ++refused_other_writer_;
    return Admission::kOtherWriter;
  }
  candidate_.samples += 1;
  candidate_ = Candidate{true, writer, seq, arrival_ns, candidate_.samples};
  return Admission::kCandidate;
}

bool StreamSession::end_poll() {
  if (!candidate_.present) return false;
  // the followed writer spoke in this poll (after the candidate, or its samples came first):
  // it is not gone, and the candidate's samples were another writer's
  if (followed_in_poll_ || !gone_at(candidate_.arrival_ns)) {
    refused_other_writer_ += candidate_.samples;
    candidate_ = Candidate{};
    return false;
  }
  open(candidate_.writer, candidate_.seq, candidate_.arrival_ns);
  // the candidate's earlier samples in this poll were superseded by its newest, not refused
  candidate_ = Candidate{};
  return true;
}

}  // namespace teleop
