#pragma once
// The counts of a recording in progress: of everything appended, and as of the last commit, so
// that a transaction lost to a full disk is taken back out of them.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "teleop/bag/bag_types.h"

namespace teleop::bag {

class RecordingTally {
 public:
  /// A new topic (ids count from 1), with no messages yet.
  void add_topic();
  /// One message appended to the open transaction.
  void add(int topic_id, int64_t recv_ns, size_t bytes);
  /// The open transaction was committed.
  void commit();
  /// The open transaction was rolled back: back to the counts of the last commit.
  void roll_back();

  /// Everything appended (after a roll back: committed).
  const BagStats& stats() const { return now_.stats; }
  /// Messages per topic, index topic_id - 1.
  const std::vector<uint64_t>& topic_counts() const { return now_.topic_counts; }

 private:
  struct Counts {
    BagStats stats;
    std::vector<uint64_t> topic_counts;
  };
  Counts now_;
  Counts committed_;
};

}  // namespace teleop::bag
