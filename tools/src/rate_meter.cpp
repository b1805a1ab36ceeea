#include "teleop/tools/rate_meter.h"

#include <algorithm>
#include <cmath>

namespace teleop::tools {

void RateMeter::add(int64_t arrival_ns, int64_t age_ns, const WriterId& writer, uint64_t seq) {
  ++received_;
  arrivals_.push_back({arrival_ns, age_ns});
  if (arrivals_.size() > capacity_) arrivals_.pop_front();
  auto [it, first] = writers_.try_emplace(writer.bytes);
  WriterRun& run = it->second;
  if (first) {
    run = {seq, seq, arrival_ns, arrival_ns};
  } else if (seq > run.last_seq) {
    lost_ += seq - run.last_seq - 1;
    run.last_seq = seq;
    run.last_ns = arrival_ns;
  }
  newest_writer_ = writer;
}

RateStats RateMeter::stats() const {
  RateStats s;
  s.received = received_;
  s.lost = lost_;
  s.window = arrivals_.size();
  if (const auto it = writers_.find(newest_writer_.bytes); it != writers_.end()) {
    s.first_seq = it->second.first_seq;
    s.last_seq = it->second.last_seq;
    s.span_s = static_cast<double>(it->second.last_ns - it->second.first_ns) * 1e-9;
  }
  if (arrivals_.empty()) return s;
  double age_sum = 0.0;
  for (const Arrival& a : arrivals_) {
    age_sum += static_cast<double>(a.age_ns) * 1e-9;
    s.age_max_s = std::max(s.age_max_s, static_cast<double>(a.age_ns) * 1e-9);
  }
  s.age_mean_s = age_sum / static_cast<double>(arrivals_.size());
  if (arrivals_.size() < 2) return s;
  double sum = 0.0, sum_sq = 0.0;
  s.period_min_s = INFINITY;
  for (size_t i = 1; i < arrivals_.size(); ++i) {
    const double p = static_cast<double>(arrivals_[i].t_ns - arrivals_[i - 1].t_ns) * 1e-9;
    sum += p;
    sum_sq += p * p;
    s.period_min_s = std::min(s.period_min_s, p);
    s.period_max_s = std::max(s.period_max_s, p);
  }
  const double n = static_cast<double>(arrivals_.size() - 1);
  s.period_mean_s = sum / n;
  s.period_std_s = std::sqrt(std::max(0.0, sum_sq / n - s.period_mean_s * s.period_mean_s));
  s.rate_hz = sum > 0 ? n / sum : 0.0;
  return s;
}

}  // namespace teleop::tools
