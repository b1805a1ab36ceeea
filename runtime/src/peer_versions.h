#pragma once
// Whether a node of another protocol or message version is on the domain (docs/versions.md): two
// releases whose messages differ exchange bytes that decode as garbage, so a node that hears such
// a peer stops (runtime/src/emergency_stop_gate.h) and says who it is and what both speak. Every
// node's status carries its versions first after the header, where any release reads them; a
// status with protocol version 0 (a tool's, a test's) says nothing and is not judged.
//
// The statuses are read on a Fast DDS thread (deserializing one allocates); the loop reads an atomic
// and, for its log, tries the lock of the words.

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

/// The peer of another version heard last, and what both speak.
struct VersionMismatch {
  FixedText<32> peer;
  uint32_t peer_protocol = 0;
  FixedText<32> peer_messages;
  FixedText<32> peer_software;
};

class PeerVersions {
 public:
  /// A mismatch is forgotten once the peer's last status is this old (it stopped, or left).
  static constexpr int64_t kForgetNs = 3'000'000'000;

  PeerVersions(transport::Participant& participant, std::string self_name);
  /// Waits for a status being judged on Fast DDS's thread; none is judged after.
  ~PeerVersions() { gate_.close(); }
  PeerVersions(const PeerVersions&) = delete;
  PeerVersions& operator=(const PeerVersions&) = delete;

  /// A peer of another version was heard within kForgetNs of `now_mono_ns`. Real-time safe.
  bool mismatched(int64_t now_mono_ns) const {
    const int64_t seen = mismatch_seen_ns_.load(std::memory_order_acquire);
    return seen != 0 && now_mono_ns - seen < kForgetNs;
  }
  /// Copies the last mismatch into `out` unless the words are being written; false then. Real-time safe.
  bool last_mismatch(VersionMismatch& out) const;

 private:
  void judge(const msg::NodeStatus& status);  // Fast DDS's thread

  std::string self_;
  std::atomic<int64_t> mismatch_seen_ns_{0};
  mutable std::mutex words_;  // the loop only tries it
  VersionMismatch last_;
  transport::CallbackGate gate_;  // closed first when this goes: judge() never outlives it
  transport::Reader<msg::NodeStatus> statuses_;  // last: its thread may call judge() at once
};

}  // namespace teleop::runtime
