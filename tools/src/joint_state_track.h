#pragma once
// The joint positions of a JointState topic over time, recorded or live, and how far two such
// tracks are apart when lined up by their start: the replay's regression measure.

#include <cstdint>
#include <string>
#include <vector>

#include "teleop/bag/bag_reader.h"

namespace teleop::tools {

struct TrackComparison {
  uint64_t samples = 0;
  /// Over every joint of every compared sample [rad].
  double rmse = 0.0;
  double max_error = 0.0;
};

class JointStateTrack {
 public:
  /// The topic's samples in the recording, at their receive times (CLOCK_MONOTONIC of the
  /// recorder). Throws std::runtime_error when the recording has no such topic.
  static JointStateTrack from_bag(bag::BagReader& reader, const std::string& topic);
  /// A serialized JointState that arrived at `t_ns`; bytes that do not decode are skipped.
  void add(int64_t t_ns, const std::vector<uint8_t>& cdr);

  size_t size() const { return t_ns_.size(); }
  /// The sample nearest to `t_ns` (times are increasing); -1 when the track is empty or `t_ns`
  /// lies outside it.
  long nearest(int64_t t_ns) const;
  int64_t time(size_t i) const { return t_ns_[i]; }
  const std::vector<double>& q(size_t i) const { return q_[i]; }

 private:
  std::vector<int64_t> t_ns_;
  std::vector<std::vector<double>> q_;
};

/// Lines the tracks up (live time - live_start = (recorded time - recorded_start) / rate) and
/// compares each live sample with the recorded one nearest to its point of the recording.
TrackComparison compare_tracks(const JointStateTrack& live, int64_t live_start_ns, const JointStateTrack& recorded,
                               int64_t recorded_start_ns, double rate);

}  // namespace teleop::tools
