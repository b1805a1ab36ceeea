#pragma once
// Lock-step runs of one node against a scripted peer, for traces that are the same bit for bit on
// every run: the peer's inputs of a cycle are in the node's readers before the node cycles, so no
// cycle depends on when UDP delivered (intra-process delivery is off, transport/qos_profile_loader.cpp).
//
// Arrival is seen by a probe, a reader of the same topic in the node's own participant (a lost
// datagram is sent again), and then made sure of for the node's own readers by a fence
// (DeliveryFence, below). The trace is folded into a 64-bit FNV-1a hash of the
// rows' bytes, so a golden hash taken before a refactoring tells whether it changed a bit.

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "node_harness.h"
#include "teleop/transport/reader.h"
#include "teleop/transport/subscription.h"
#include "teleop/transport/topics.h"

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

/// A stream the scripted peer writes to the node: its publication and its probe.
template <typename T>
struct ScriptedStream {
  ScriptedStream(transport::Participant& peer, transport::Participant& node, const transport::TopicSpec<T>& topic,
                 const std::string& source)
      : publication(peer, topic, source), probe(node, topic) {}
  T& sample() { return publication.sample(); }
  /// Publishes the sample and waits until the node's participant has it (deliver()).
  bool deliver() { return test::deliver(publication, probe); }
  /// The node's reader and the probe: both matched (`readers` 2), or only the probe.
  bool matched(int readers = 2) const { return publication.matched() >= readers; }

  transport::Publication<T> publication;
  ArrivalProbe<T> probe;
};

/// Makes sure the node's readers have what its probes have. The samples of the peer reach the
/// node's participant on one socket, handled in order by one receive thread, each datagram handed
/// to every matched reader before the next: a reliable sample sent after them (a NodeStatus of no
/// flows, which no node acts on) is seen by a reader of the node's participant only once every
/// reader there has the samples sent before it.
class DeliveryFence {
 public:
  DeliveryFence(transport::Participant& peer, transport::Participant& node)
      : fence_(peer, transport::topics::kNodeStatus, "lockstep_fence"),
        seen_(node.make_reader(transport::topics::kNodeStatus)) {}
  bool matched() const { return fence_.matched() > 0; }
  /// Sends a fence and waits until it arrived (false after 5 s).
  bool pass() {
    if (!fence_.publish()) return false;
    return eventually(
        [&] {
          while (seen_.take_next(sample_)) {
            if (std::string_view(sample_.header().source().c_str()) == "lockstep_fence" &&
                sample_.header().seq() == fence_.sent())
              return true;
          }
          return false;
        },
        std::chrono::seconds(5));
  }

 private:
  transport::Publication<msg::NodeStatus> fence_;
  transport::Reader<msg::NodeStatus> seen_;
  msg::NodeStatus sample_;
};

/// The columns of a trace that a hash compares: all but those added after its hashes were taken,
/// so that the columns they were taken over still compare bit for bit.
class HashedColumns {
 public:
  HashedColumns(const std::vector<std::string>& columns, std::initializer_list<std::string_view> added_since) {
    for (size_t i = 0; i < columns.size(); ++i) {
      if (std::find(added_since.begin(), added_since.end(), columns[i]) == added_since.end()) kept_.push_back(i);
    }
    missing_ = added_since.size() - (columns.size() - kept_.size());
    values_.resize(kept_.size());
  }
  /// Names in `added_since` the trace does not have (0: the list is the trace's).
  size_t missing() const { return missing_; }
  /// The kept values of `row`.
  std::span<const double> of(std::span<const double> row) {
    for (size_t k = 0; k < kept_.size(); ++k) values_[k] = row[kept_[k]];
    return values_;
  }

 private:
  std::vector<size_t> kept_;
  std::vector<double> values_;
  size_t missing_ = 0;
};

/// 64-bit FNV-1a over the bytes of trace rows: equal hashes, equal traces (to the bit). With
/// TELEOP_LOCKSTEP_DUMP=DIR the rows also go to DIR/<name>.txt in hex floats, to find the first
/// row and column two runs differ in.
class TraceHash {
 public:
  explicit TraceHash(const std::string& name) {
    if (const char* dir = std::getenv("TELEOP_LOCKSTEP_DUMP"))
      dump_ = std::fopen((std::string(dir) + "/" + name + ".txt").c_str(), "w");
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
