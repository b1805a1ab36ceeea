#pragma once
// Whether a node on the domain disagrees with this one on what they must share (docs/versions.md,
// docs/architectures.md): a peer of another protocol or message version exchanges bytes that decode
// as garbage, and a peer playing another teleoperation architecture exchanges samples that mean
// something else to it (a pfc_tdpa leader's passivity controller beside a follower that has none).
// Either way the node stops (runtime/src/emergency_stop_gate.h) and says who the peer is and what
// both say. Every node's status carries its versions first after the header, where any release
// reads them, and its architecture after them; a status with protocol version 0 (a tool's, a
// test's) says nothing and is not judged, nor is an architecture that either side leaves empty (the
// hand's CAN node, a twin outside a scenario). One architecture per domain: pairs that play
// different ones run on domains of their own.
//
// The statuses are read on a Fast DDS thread (deserializing one allocates); the loop reads an atomic
// and, for its log, tries the lock of the words.

#include <array>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>

#include <teleop/msg/status.h>

#include "teleop/common/fixed_text.h"
#include "teleop/transport/callback_gate.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/reader.h"

namespace teleop::runtime {

/// What a peer disagrees on.
enum class Disagreement : uint8_t { kVersion, kArchitecture };
inline constexpr size_t kDisagreements = 2;

/// The disagreeing peer heard last, and what it says.
struct PeerMismatch {
  FixedText<32> peer;
  uint32_t peer_protocol = 0;
  FixedText<32> peer_messages;
  FixedText<32> peer_software;
  FixedText<32> peer_architecture;
};

class PeerAgreement {
 public:
  /// A mismatch is forgotten once the peer's last status is this old (it stopped, or left).
  static constexpr int64_t kForgetNs = 3'000'000'000;

  /// `architecture`: the one this node plays; empty: none (it judges no peer's).
  PeerAgreement(transport::Participant& participant, std::string self_name, std::string architecture);
  /// Waits for a status being judged on Fast DDS's thread; none is judged after.
  ~PeerAgreement() { gate_.close(); }
  PeerAgreement(const PeerAgreement&) = delete;
  PeerAgreement& operator=(const PeerAgreement&) = delete;

  /// A peer that disagrees on `what` was heard within kForgetNs of `now_mono_ns`. Real-time safe.
  bool mismatched(Disagreement what, int64_t now_mono_ns) const {
    const int64_t seen = slots_[index(what)].seen_ns.load(std::memory_order_acquire);
    return seen != 0 && now_mono_ns - seen < kForgetNs;
  }
  /// Copies the last peer that disagreed on `what` into `out` unless the words are being written;
  /// false then. Real-time safe.
  bool last_mismatch(Disagreement what, PeerMismatch& out) const;

  const std::string& architecture() const { return architecture_; }
  /// Statuses of other nodes judged so far (a tool's included).
  uint64_t statuses_judged() const { return judged_.load(std::memory_order_acquire); }

 private:
  struct Slot {
    std::atomic<int64_t> seen_ns{0};
    PeerMismatch last;  // under words_
  };
  static size_t index(Disagreement what) { return static_cast<size_t>(what); }
  void judge(const msg::NodeStatus& status);  // Fast DDS's thread
  void record(Disagreement what, const msg::NodeStatus& status);

  std::string self_;
  std::string architecture_;
  std::array<Slot, kDisagreements> slots_{};
  std::atomic<uint64_t> judged_{0};
  mutable std::mutex words_;  // the loop only tries it
  transport::CallbackGate gate_;  // closed first when this goes: judge() never outlives it
  transport::Reader<msg::NodeStatus> statuses_;  // last: its thread may call judge() at once
};

}  // namespace teleop::runtime
