#include "teleop/transport/impairment/link_profile.h"

namespace teleop::transport::impairment {
namespace {

constexpr Range kProbability{0.0, 1.0};
constexpr Range kMs{0.0, 3'600'000.0};

int64_t ms_to_ns(double ms) { return static_cast<int64_t>(ms * 1e6); }

LossSpec parse_loss(const ConfigNode& n) {
  LossSpec loss;
  const std::string model = n.get_choice("model", {"none", "bernoulli", "gilbert_elliott"});
  if (model == "bernoulli") {
    loss.model = LossModel::kBernoulli;
    loss.probability = n.get_double("probability", kProbability);
  } else if (model == "gilbert_elliott") {
    loss.model = LossModel::kGilbertElliott;
    loss.p = n.get_double("p", kProbability);
    loss.r = n.get_double("r", kProbability);
    loss.loss_in_bad = n.get_double("loss_in_bad", kProbability, 1.0);
    loss.loss_in_good = n.get_double("loss_in_good", kProbability, 0.0);
    if (loss.r == 0 && loss.p > 0) throw n.error("r", "must be > 0: the link would never leave the bad state");
  }
  return loss;
}

// the settings of one phase; `base` supplies defaults so a phase only says what changes
LinkPhase parse_phase(const ConfigNode& n, const LinkPhase& base) {
  LinkPhase p = base;
  p.delay_ns = ms_to_ns(n.get_double("delay_ms", kMs, static_cast<double>(base.delay_ns) * 1e-6));
  p.jitter_ns = ms_to_ns(n.get_double("jitter_ms", kMs, static_cast<double>(base.jitter_ns) * 1e-6));
  const std::string dist = n.get_choice("distribution", {"constant", "uniform", "normal", "pareto"},
                                        p.jitter_ns > 0 ? "normal" : "constant");
  p.distribution = dist == "uniform"  ? DelayDistribution::kUniform
                   : dist == "normal" ? DelayDistribution::kNormal
                   : dist == "pareto" ? DelayDistribution::kPareto
                                      : DelayDistribution::kConstant;
  p.correlation = n.get_double("correlation", Range{0.0, 0.99}, base.correlation);
  if (auto loss = n.optional_child("loss")) p.loss = parse_loss(*loss);
  p.duplicate_probability = n.get_double("duplicate_probability", kProbability, base.duplicate_probability);
  if (auto reorder = n.optional_child("reorder")) {
    p.reorder_probability = reorder->get_double("probability", kProbability);
    p.reorder_gap = static_cast<uint32_t>(reorder->get_int("gap", Range{1, 1e6}, 1));
  }
  if (auto rate = n.optional_child("rate")) {
    p.rate_bps = rate->get_double("bandwidth_mbps", Range{0.001, 1e6}) * 1e6;
    p.queue_limit = static_cast<uint32_t>(rate->get_int("queue_messages", Range{1, 4096}, 1000));
  }
  p.down = n.get_bool("down", false);
  return p;
}

}  // namespace

double LossSpec::expected_loss_rate() const {
  switch (model) {
    case LossModel::kNone: return 0.0;
    case LossModel::kBernoulli: return probability;
    case LossModel::kGilbertElliott: {
      if (p + r <= 0) return loss_in_good;
      const double bad = p / (p + r);
      return bad * loss_in_bad + (1.0 - bad) * loss_in_good;
    }
  }
  return 0.0;
}

bool LinkProfile::is_transparent() const {
  if (!outages.empty()) return false;
  for (const auto& p : phases) {
    if (p.delay_ns != 0 || p.jitter_ns != 0 || p.loss.model != LossModel::kNone || p.duplicate_probability > 0 ||
        p.reorder_probability > 0 || p.rate_bps > 0 || p.down) {
      return false;
    }
  }
  return true;
}

LinkProfile parse_link_profile(const ConfigNode& n) {
  LinkProfile profile;
  profile.name = n.get_string("name");
  // the top level is the first (or only) phase; `phases` lists what follows, each for its duration
  LinkPhase first = parse_phase(n, LinkPhase{});
  const auto phases = n.get_node_list("phases");
  profile.phases = {first};
  if (!phases.empty()) {
    profile.phases.front().duration_ns = ms_to_ns(n.get_double("duration_s", Range{0.001, 1e6}) * 1e3);
    for (size_t i = 0; i < phases.size(); ++i) {
      LinkPhase next = parse_phase(phases[i], first);
      const bool last = i + 1 == phases.size();
      next.duration_ns = last ? 0 : ms_to_ns(phases[i].get_double("duration_s", Range{0.001, 1e6}) * 1e3);
      if (last) phases[i].get_double("duration_s", Range{0, 1e6}, 0);  // allowed, ignored: the last lasts
      profile.phases.push_back(next);
    }
  } else {
    n.get_double("duration_s", Range{0, 1e6}, 0);  // a single phase lasts forever
  }
  for (const ConfigNode& o : n.get_node_list("outages")) {
    profile.outages.push_back({ms_to_ns(o.get_double("start_s", Range{0, 1e6}) * 1e3),
                               ms_to_ns(o.get_double("duration_s", Range{0.001, 1e6}) * 1e3)});
  }
  return profile;
}

LinkProfile load_link_profile(const std::string& path) {
  const ConfigNode root = ConfigNode::load_file(path);
  LinkProfile profile = parse_link_profile(root.child("profile"));
  root.check_all_used();
  return profile;
}

}  // namespace teleop::transport::impairment
