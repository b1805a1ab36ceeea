#pragma once
// Which writer a stream follows. A reader takes the samples of one writer at a time (a session)
// and lets another writer take over only once that one has gone quiet: a restarted peer (a new
// DDS writer, sequence numbers from 1 again) is followed as soon as its first sample arrives, and
// a stray or forged writer is refused for as long as the followed one keeps talking. Sequence
// numbers are compared within a session only, so no sample of any writer can hold a stream.

#include <array>
#include <cstdint>

namespace teleop {

/// A writer's identity as the middleware gives it (for DDS: the GUID of the DataWriter).
struct WriterId {
  std::array<uint8_t, 16> bytes{};
  bool operator==(const WriterId&) const = default;
};

/// What a stream makes of one sample.
enum class Admission {
  kNewSession,    ///< the first sample of a session (the first writer, or one taking over)
  kNewest,        ///< the followed writer's, newer than any before
  kOlder,         ///< the followed writer's, not newer than its newest (duplicate or reordered)
  kOtherWriter,   ///< another writer's while the followed one still talks: refused
  kSequenceJump,  ///< the followed writer's, but its sequence number leapt beyond the bound: refused
};

/// True for the admissions that make the sample the stream's newest.
inline bool is_newest(Admission a) { return a == Admission::kNewSession || a == Admission::kNewest; }

struct StreamSessionPolicy {
  /// The followed writer counts as gone once its newest sample is this old; the next sample of
  /// any writer then opens a new session.
  int64_t takeover_silence_ns = 100'000'000;
  /// A forward leap of the sequence number beyond this is refused while the writer is not gone (a
  /// live writer cannot skip 65 s of samples at 1 kHz between two of our polls).
  uint64_t max_sequence_jump = uint64_t{1} << 16;
};

/// Decides, sample by sample, whether a stream takes it. Real-time safe, no allocation.
class StreamSession {
 public:
  explicit StreamSession(StreamSessionPolicy policy = {}) : policy_(policy) {}

  /// Admits or refuses the sample `seq` of `writer`, seen at `now_mono_ns` (CLOCK_MONOTONIC).
  [[nodiscard]] Admission admit(const WriterId& writer, uint64_t seq, int64_t now_mono_ns);

  /// Sessions opened so far (0 before the first sample); identifies the current one.
  uint64_t session() const { return session_; }
  /// Samples refused because another writer was being followed.
  uint64_t refused_other_writer() const { return refused_other_writer_; }
  /// Samples refused for a sequence number that leapt beyond the bound.
  uint64_t refused_sequence_jump() const { return refused_sequence_jump_; }
  const StreamSessionPolicy& policy() const { return policy_; }

 private:
  Admission open(const WriterId& writer, uint64_t seq, int64_t now_mono_ns);

  StreamSessionPolicy policy_;
  uint64_t session_ = 0;
  WriterId writer_{};
  uint64_t last_seq_ = 0;
  int64_t last_newest_ns_ = 0;
  uint64_t refused_other_writer_ = 0;
  uint64_t refused_sequence_jump_ = 0;
};

}  // namespace teleop
