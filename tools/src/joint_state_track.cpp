#include "joint_state_track.h"

#include <fastdds/rtps/common/SerializedPayload.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "teleop/transport/type_support.h"

namespace teleop::tools {

JointStateTrack JointStateTrack::from_bag(bag::BagReader& reader, const std::string& topic) {
  const int id = reader.topic_id(topic);
  if (id < 0) throw std::runtime_error("the recording has no topic " + topic + " to compare with");
  JointStateTrack track;
  reader.select({id});
  bag::BagMessage m;
  while (reader.next(m)) track.add(bag::pacing_time_ns(m), m.data);
  return track;
}

void JointStateTrack::add(int64_t t_ns, const std::vector<uint8_t>& cdr) {
  transport::PubSubTypeOf<msg::JointState>::type support;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<uint32_t>(cdr.size()));
  std::memcpy(payload.data, cdr.data(), cdr.size());
  payload.length = static_cast<uint32_t>(cdr.size());
  msg::JointState state;
  try {
    if (!support.deserialize(&payload, &state)) return;
  } catch (const std::exception&) {
    return;  // fastcdr throws on bytes too short for what it reads
  }
  if (!t_ns_.empty() && t_ns < t_ns_.back()) return;  // keep the track ordered
  t_ns_.push_back(t_ns);
  q_.push_back(state.q_rad());
}

long JointStateTrack::nearest(int64_t t_ns) const {
  if (t_ns_.empty() || t_ns < t_ns_.front() || t_ns > t_ns_.back()) return -1;
  const auto it = std::lower_bound(t_ns_.begin(), t_ns_.end(), t_ns);
  long i = static_cast<long>(it - t_ns_.begin());
  if (i > 0 && (it == t_ns_.end() || t_ns - t_ns_[static_cast<size_t>(i - 1)] < *it - t_ns)) --i;
  return i;
}

TrackComparison compare_tracks(const JointStateTrack& live, int64_t live_start_ns, const JointStateTrack& recorded,
                               int64_t recorded_start_ns, double rate) {
  TrackComparison c;
  double sum_sq = 0.0;
  uint64_t values = 0;
  for (size_t i = 0; i < live.size(); ++i) {
    if (live.time(i) < live_start_ns) continue;
    const auto at = recorded_start_ns + static_cast<int64_t>(static_cast<double>(live.time(i) - live_start_ns) * rate);
    const long r = recorded.nearest(at);
    if (r < 0) continue;
    const auto& a = live.q(i);
    const auto& b = recorded.q(static_cast<size_t>(r));
    for (size_t j = 0; j < std::min(a.size(), b.size()); ++j) {
      const double e = a[j] - b[j];
      sum_sq += e * e;
      c.max_error = std::max(c.max_error, std::abs(e));
      ++values;
    }
    ++c.samples;
  }
  c.rmse = values > 0 ? std::sqrt(sum_sq / static_cast<double>(values)) : 0.0;
  return c;
}

}  // namespace teleop::tools
