#pragma once
// Which writer a stream follows. A reader takes the samples of one writer at a time (a session)
// and lets another writer take over only once that one has gone quiet: a restarted peer (a new
// DDS writer, sequence numbers from 1 again) is followed as soon as its first sample arrives, and
// a stray or forged writer is refused for as long as the followed one keeps talking. Sequence
// numbers are compared within a session only, so no sample of any writer can hold a stream.
//
// Silence is judged from the followed writer's own arrival times, and a takeover is decided only
// after the whole poll was drained: after a stall of the reader (its process stopped, its loop
// starved) the backlog holds both writers' samples in any order, and the followed writer is not
// gone merely because another writer's sample came out first. Time the reader spent not polling
// does not count as silence either: after a gap between polls, the followed writer is given a
// whole silence period of listening before anyone may take over.

#include <array>
#include <cstddef>
#include <cstdint>

namespace teleop {

/// A writer's identity as the middleware gives it (for DDS: the GUID of the DataWriter).
struct WriterId {
  std::array<uint8_t, 16> bytes{};
  bool operator==(const WriterId&) const = default;

  /// The 16 bytes as 32 lower-case hex digits and a terminating zero (how a status names it).
  std::array<char, 33> hex() const {
    static constexpr char kDigits[] = "0123456789abcdef";
    std::array<char, 33> text{};
    for (std::size_t i = 0; i < bytes.size(); ++i) {
      text[2 * i] = kDigits[bytes[i] >> 4];
      text[2 * i + 1] = kDigits[bytes[i] & 0xf];
    }
    return text;
  }
};

/// What a stream makes of one sample.
enum class Admission {
  kNewSession,    ///< the first sample of the first session
  kNewest,        ///< the followed writer's, newer than any before
  kOlder,         ///< the followed writer's, not newer than its newest (duplicate or reordered)
  kOtherWriter,   ///< another writer's while the followed one still talks: refused
  kSequenceJump,  ///< the followed writer's, but its sequence number leapt beyond the bound: refused
  kCandidate,     ///< another writer's after the followed one went quiet: it takes over at the end
                  ///< of the poll unless the followed writer turns up in the same poll
};

/// True for the admissions that make the sample the stream's newest.
inline bool is_newest(Admission a) { return a == Admission::kNewSession || a == Admission::kNewest; }

struct StreamSessionPolicy {
  /// The followed writer counts as gone once its newest sample is this old; another writer's
  /// sample then opens a new session.
  int64_t takeover_silence_ns = 100'000'000;
  /// A forward leap of the sequence number beyond this is refused while the writer is not gone (a
  /// live writer cannot skip 65 s of samples at 1 kHz between two of our polls).
  uint64_t max_sequence_jump = uint64_t{1} << 16;
};

/// Decides, sample by sample, whether a stream takes it. Real-time safe, no allocation.
///
/// A poll: begin_poll(), admit() for each sample in arrival order, end_poll(). A kCandidate
/// sample is kept aside by the caller; end_poll() says whether it became the first of a new
/// session.
class StreamSession {
 public:
  explicit StreamSession(StreamSessionPolicy policy = {}) : policy_(policy) {}

  /// Starts a poll at `now_mono_ns` (CLOCK_MONOTONIC).
  void begin_poll(int64_t now_mono_ns);
  /// Admits or refuses the sample `seq` of `writer` that arrived at `arrival_mono_ns`.
  [[nodiscard]] Admission admit(const WriterId& writer, uint64_t seq, int64_t arrival_mono_ns);
  /// Ends the poll: true when the candidate (the last kCandidate sample) took the stream over.
  [[nodiscard]] bool end_poll();

  /// Sessions opened so far (0 before the first sample); identifies the current one.
  uint64_t session() const { return session_; }
  /// The followed writer (valid once session() > 0).
  const WriterId& writer() const { return writer_; }
  /// Samples refused because another writer was being followed (candidates that lost included).
  uint64_t refused_other_writer() const { return refused_other_writer_; }
  /// Samples refused for a sequence number that leapt beyond the bound.
  uint64_t refused_sequence_jump() const { return refused_sequence_jump_; }
  const StreamSessionPolicy& policy() const { return policy_; }

 private:
  struct Candidate {
    bool present = false;
    WriterId writer{};
    uint64_t seq = 0;
    int64_t arrival_ns = 0;
    uint64_t samples = 0;
  };

  void open(const WriterId& writer, uint64_t seq, int64_t arrival_ns);
  Admission admit_followed(uint64_t seq, int64_t arrival_ns);
  Admission admit_other(const WriterId& writer, uint64_t seq, int64_t arrival_ns);
  /// Whether the followed writer has been silent, while we listened, for the takeover silence at `t`.
  bool gone_at(int64_t t) const;

  StreamSessionPolicy policy_;
  uint64_t session_ = 0;
  WriterId writer_{};
  uint64_t last_seq_ = 0;
  int64_t last_newest_ns_ = 0;  // arrival of the followed writer's newest sample
  bool polled_ = false;
  int64_t last_poll_ns_ = 0;
  int64_t listening_since_ns_ = 0;  // since when the polls came without a gap
  bool followed_in_poll_ = false;
  Candidate candidate_;
  uint64_t refused_other_writer_ = 0;
  uint64_t refused_sequence_jump_ = 0;
};

}  // namespace teleop
