#include "teleop/transport/impairment/link_model.h"

#include <algorithm>
#include <cmath>

namespace teleop::transport::impairment {

const char* to_string(DropReason reason) {
  switch (reason) {
    case DropReason::kNone: return "none";
    case DropReason::kLoss: return "loss";
    case DropReason::kOutage: return "outage";
    case DropReason::kQueue: return "queue";
  }
  return "?";
}

LinkModel::LinkModel(const LinkProfile& profile, uint64_t seed, int64_t start_ns)
    : profile_(profile), rng_(seed), start_ns_(start_ns), phase_end_ns_(profile.phases.front().duration_ns) {
  if (profile_.phases.empty()) profile_.phases.push_back(LinkPhase{});
}

const LinkPhase& LinkModel::phase_at(int64_t elapsed_ns) {
  // phases only move forward; the last one lasts forever
  while (phase_index_ + 1 < profile_.phases.size() && elapsed_ns >= phase_end_ns_) {
    ++phase_index_;
    phase_end_ns_ += profile_.phases[phase_index_].duration_ns;
  }
  return profile_.phases[phase_index_];
}

bool LinkModel::in_outage(int64_t elapsed_ns) const {
  for (const auto& o : profile_.outages) {
    if (elapsed_ns >= o.start_ns && elapsed_ns < o.start_ns + o.duration_ns) return true;
  }
  return false;
}

bool LinkModel::lose(const LossSpec& loss) {
  // always two draws per message, so that decisions stay aligned whatever the model
  const double u_state = rng_.uniform();
  const double u_loss = rng_.uniform();
  switch (loss.model) {
    case LossModel::kNone: return false;
    case LossModel::kBernoulli: return u_loss < loss.probability;
    case LossModel::kGilbertElliott:
      ge_bad_ = ge_bad_ ? !(u_state < loss.r) : (u_state < loss.p);
      return u_loss < (ge_bad_ ? loss.loss_in_bad : loss.loss_in_good);
  }
  return false;
}

int64_t LinkModel::draw_delay(const LinkPhase& phase) {
  const double u = delay_uniform_.next(rng_, phase.correlation);
  const auto jitter = static_cast<double>(phase.jitter_ns);
  double delay = static_cast<double>(phase.delay_ns);
  switch (phase.distribution) {
    case DelayDistribution::kConstant: break;
    case DelayDistribution::kUniform: delay += jitter * (2.0 * u - 1.0); break;
    case DelayDistribution::kNormal: delay += jitter * inverse_normal_cdf(u); break;
    case DelayDistribution::kPareto: delay += jitter * standard_pareto(u); break;
  }
  return std::max<int64_t>(0, std::llround(delay));
}

bool LinkModel::rate_limit(const LinkPhase& phase, int64_t now_ns, uint32_t bytes, int64_t& ready_ns) {
  ready_ns = now_ns;
  if (phase.rate_bps <= 0) return true;
  // forget the messages that finished serialising before now
  while (queue_size_ > 0 && queue_finish_ns_[queue_head_] <= now_ns) {
    queue_head_ = (queue_head_ + 1) % kMaxQueue;
    --queue_size_;
  }
  if (queue_size_ >= std::min<size_t>(phase.queue_limit, kMaxQueue)) return false;
  const int64_t start = std::max(now_ns, link_free_ns_);
  link_free_ns_ = start + static_cast<int64_t>(std::ceil(static_cast<double>(bytes) * 8e9 / phase.rate_bps));
  queue_finish_ns_[(queue_head_ + queue_size_) % kMaxQueue] = link_free_ns_;
  ++queue_size_;
  ready_ns = link_free_ns_;
  return true;
}

Decision LinkModel::decide(int64_t now_ns, uint32_t bytes) {
  const int64_t elapsed = now_ns - start_ns_;
  const LinkPhase& phase = phase_at(elapsed);
  // every draw happens for every message, in the same order: decisions depend on the seed and
  // the message sequence only, not on which branch an earlier message took
  const bool lost = lose(phase.loss);
  const int64_t delay = draw_delay(phase);
  const bool duplicate = rng_.uniform() < phase.duplicate_probability;
  const double u_reorder = rng_.uniform();

  Decision d;
  int64_t ready_ns = now_ns;
  if (phase.down || in_outage(elapsed)) {
    d.drop = DropReason::kOutage;
  } else if (lost) {
    d.drop = DropReason::kLoss;
  } else if (!rate_limit(phase, now_ns, bytes, ready_ns)) {
    d.drop = DropReason::kQueue;
  }
  if (d.drop == DropReason::kNone) {
    const bool reorder_candidate = phase.reorder_gap <= 1 || (reorder_counter_++ % phase.reorder_gap) == 0;
    d.reordered = reorder_candidate && u_reorder < phase.reorder_probability;
    int64_t at = ready_ns + delay;
    if (d.reordered) {
      at = ready_ns;  // skips the delay line, overtaking what is queued
    } else {
      at = std::max(at, last_delivery_ns_);  // keep order: never overtake an earlier message
      last_delivery_ns_ = at;
    }
    d.copies = duplicate ? 2 : 1;
    d.deliver_at_ns = {at, at};
  }
  record(d, now_ns);
  return d;
}

void LinkModel::record(const Decision& d, int64_t now_ns) {
  ++stats_.messages;
  switch (d.drop) {
    case DropReason::kNone: break;
    case DropReason::kLoss: ++stats_.lost; break;
    case DropReason::kOutage: ++stats_.outage; break;
    case DropReason::kQueue: ++stats_.queue; break;
  }
  if (d.drop != DropReason::kNone) {
    ++current_loss_run_;
    return;
  }
  if (current_loss_run_ > 0) stats_.loss_runs.record(static_cast<int64_t>(current_loss_run_));
  current_loss_run_ = 0;
  stats_.delivered += static_cast<uint64_t>(d.copies);
  if (d.copies == 2) ++stats_.duplicated;
  if (d.reordered) ++stats_.reordered;
  stats_.delay.record(d.deliver_at_ns[0] - now_ns);
}

}  // namespace teleop::transport::impairment
