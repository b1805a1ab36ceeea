#pragma once
// Lock-step runs of one node against a scripted peer, for traces that are the same bit for bit on
// every run: the peer's inputs of a cycle are in the node's readers before the node cycles, so no
// cycle depends on when UDP delivered (intra-process delivery is off, transport/qos_profile_loader.cpp).
//
// Arrival is seen by a probe: a reader of the same topic in the node's own participant. A
// participant hands each datagram to all its matched readers in one pass of its receive thread,
// so once the probe has a sample the node's reader has it too, or within microseconds; the
// margin after the probe covers that. The trace is folded into a 64-bit FNV-1a hash of the
// rows' bytes, so a golden hash taken before a refactoring tells whether it changed a bit.

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <span>
#include <thread>

#include "node_harness.h"
#include "teleop/transport/subscription.h"

namespace teleop::test {

/// A reader in the node's participant that tells when the peer's newest sample has arrived.
template <typename T>
class ArrivalProbe {
 public:
  ArrivalProbe(transport::Participant& node_participant, const transport::TopicSpec<T>& topic)
      : probe_(node_participant, topic) {}
  /// Waits until a sample arrived since the last call (false after `timeout`).
  bool arrived(std::chrono::microseconds timeout) {
    const auto until = std::chrono::steady_clock::now() + timeout;
    while (probe_.poll() == 0) {
      if (std::chrono::steady_clock::now() > until) return false;
      std::this_thread::sleep_for(std::chrono::microseconds(20));
    }
    return true;
  }

 private:
  transport::Subscription<T> probe_;
};

/// Publishes the sample and waits until the node's participant has it: the streams are best
/// effort, and a datagram lost on a loaded machine is sent again, the same sample with the same
/// sequence number (Publication::resend). False after 100 tries.
template <typename T>
bool deliver(transport::Publication<T>& publication, ArrivalProbe<T>& probe) {
  if (!publication.publish()) return false;
  for (int attempt = 0; attempt < 100; ++attempt) {
    if (probe.arrived(std::chrono::milliseconds(50))) return true;
    if (!publication.resend()) return false;
  }
  return false;
}

/// Time for the node's own readers after the probe saw a sample (same receive pass, see above).
inline void delivery_margin() { std::this_thread::sleep_for(std::chrono::microseconds(300)); }

/// 64-bit FNV-1a over the bytes of trace rows: equal hashes, equal traces (to the bit). With
/// TELEOP_LOCKSTEP_DUMP=DIR the rows also go to DIR/<name>.txt in hex floats, to find the first
/// row and column two runs differ in.
class TraceHash {
 public:
  explicit TraceHash(const std::string& name) {
    if (const char* dir = std::getenv("TELEOP_LOCKSTEP_DUMP")) dump_ = std::fopen((std::string(dir) + "/" + name + ".txt").c_str(), "w");
  }
  ~TraceHash() {
    if (dump_ != nullptr) std::fclose(dump_);
  }
  TraceHash(const TraceHash&) = delete;
  TraceHash& operator=(const TraceHash&) = delete;

  void add(std::span<const double> row) {
    if (dump_ != nullptr) {
      for (double v : row) std::fprintf(dump_, "%a ", v);
      std::fprintf(dump_, "\n");
    }
    for (double v : row) {
      uint64_t bits = 0;
      std::memcpy(&bits, &v, sizeof bits);
      for (int b = 0; b < 8; ++b) {
        hash_ ^= (bits >> (8 * b)) & 0xffu;
        hash_ *= 0x100000001b3ull;
      }
    }
    ++rows_;
  }
  uint64_t value() const { return hash_; }
  uint64_t rows() const { return rows_; }

 private:
  std::FILE* dump_ = nullptr;
  uint64_t hash_ = 0xcbf29ce484222325ull;
  uint64_t rows_ = 0;
};

}  // namespace teleop::test
