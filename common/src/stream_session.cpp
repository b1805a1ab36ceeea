#include "teleop/common/stream_session.h"

namespace teleop {

Admission StreamSession::open(const WriterId& writer, uint64_t seq, int64_t now_mono_ns) {
  ++session_;
  writer_ = writer;
  last_seq_ = seq;
  last_newest_ns_ = now_mono_ns;
  return Admission::kNewSession;
}

Admission StreamSession::admit(const WriterId& writer, uint64_t seq, int64_t now_mono_ns) {
  if (session_ == 0) return open(writer, seq, now_mono_ns);
  const bool gone = now_mono_ns - last_newest_ns_ >= policy_.takeover_silence_ns;
  if (!(writer == writer_)) {
    if (gone) return open(writer, seq, now_mono_ns);
    ++refused_other_writer_;
    return Admission::kOtherWriter;
  }
  if (seq > last_seq_) {
    if (seq - last_seq_ > policy_.max_sequence_jump && !gone) {
      ++refused_sequence_jump_;
      return Admission::kSequenceJump;
    }
    last_seq_ = seq;
    last_newest_ns_ = now_mono_ns;
    return Admission::kNewest;
  }
  // a writer never numbers backwards: one that does after going quiet started afresh (or was
  // forged high before), and following it again is what keeps the stream from locking
  if (seq < last_seq_ && gone) return open(writer, seq, now_mono_ns);
  return Admission::kOlder;
}

}  // namespace teleop
