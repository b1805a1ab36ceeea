#include "teleop/control/passivity.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace teleop::control {
namespace {

const PassivityPortConfig& validated(const PassivityPortConfig& config) {
  if (config.channels == 0 || config.channels > kMaxTdpaChannels) {
    throw std::invalid_argument("PassivityPortConfig.channels must be 1.." + std::to_string(kMaxTdpaChannels) +
                                ", got " + std::to_string(config.channels));
  }
  if (!(config.cycle_s > 0.0) || !std::isfinite(config.cycle_s)) {
    throw std::invalid_argument("PassivityPortConfig.cycle_s must be finite and > 0, got " +
                                std::to_string(config.cycle_s));
  }
  if (!(config.max_damping > 0.0)) {
    throw std::invalid_argument("PassivityPortConfig.max_damping must be > 0 (infinity: no limit), got " +
                                std::to_string(config.max_damping));
  }
  return config;
}

}  // namespace

PassivityPort::PassivityPort(const PassivityPortConfig& config) : config_(validated(config)), remote_(config.channels) {
  packet_.channels = config_.channels;
}

PortStatus PassivityPort::update(std::span<const double> force, std::span<const double> velocity,
                                 std::span<double> corrected) {
  const std::size_t n = config_.channels;
  if (force.size() != n || velocity.size() != n || corrected.size() != n) {
    ++counters_.size_mismatches;
    return PortStatus::kSizeMismatch;
  }
  ++counters_.cycles;
  bool saturated = false;
  bool non_finite = false;
  for (std::size_t i = 0; i < n; ++i) {
    const double f = force[i];
    const double v = velocity[i];
    if (!std::isfinite(f) || !std::isfinite(v)) {
      // a safe output (no force, no motion) and no energy this cycle
      ++counters_.non_finite_inputs;
      non_finite = true;
      state_[i].damping = 0.0;
      corrected[i] = 0.0;
    } else {
      corrected[i] = update_channel(i, f, v, saturated);
    }
    min_observed_j_ = std::min(min_observed_j_, observed_energy_j(i));
  }
  if (non_finite) {
    return PortStatus::kNonFiniteInput;
  }
  return saturated ? PortStatus::kSaturated : PortStatus::kOk;
}

double PassivityPort::update_channel(std::size_t i, double f, double v, bool& saturated) {
  ChannelState& s = state_[i];
  s.damping = 0.0;
  const double h = config_.cycle_s;
  const bool force_output = config_.causality == PortCausality::kForceOutput;
  const double delivered = force_output ? f : v;
  const double other = force_output ? v : f;
  const double flow_j = f * v * h;
  if (flow_j >= 0.0) {
    s.in_j += flow_j;
    return delivered;
  }
  const double out_j = -flow_j;
  const double remote_in_j = remote_.energy_in_j(i);
  // compared as the sum that will be stored, so W >= 0 holds in floating point too
  const double new_out_j = s.out_j + out_j;
  if (new_out_j <= remote_in_j) {
    s.out_j = new_out_j;
    return delivered;
  }
  ++counters_.deficits;
  if (!config_.controller_enabled) {
    s.out_j = new_out_j;
    return delivered;
  }
  // never more than this cycle's outflow: a deficit carried from a clamped cycle stops the flow
  const double deficit_j = new_out_j - std::max(s.out_j, remote_in_j);
  const double gain = deficit_j / (h * other * other);
  if (gain > config_.max_damping) {
    ++counters_.saturations;
    saturated = true;
    s.damping = config_.max_damping;
    const double dissipated_j = config_.max_damping * other * other * h;
    s.dissipated_j += dissipated_j;
    s.out_j += out_j - dissipated_j;
    return delivered + config_.max_damping * other;
  }
  s.damping = gain;
  s.dissipated_j += deficit_j;
  // W = 0 exactly (E_out = E_in^remote), or a deficit carried from a clamped cycle stays as it was
  s.out_j = std::max(s.out_j, remote_in_j);
  // delivered + gain * other, written so that it stays finite when other^2 underflows
  return delivered * std::max(0.0, 1.0 - deficit_j / out_j);
}

const EnergyPacket& PassivityPort::make_packet() {
  ++packet_.seq;
  for (std::size_t i = 0; i < config_.channels; ++i) {
    packet_.energy_in_j[i] = state_[i].in_j;
    packet_.energy_out_j[i] = state_[i].out_j;
  }
  return packet_;
}

PacketVerdict PassivityPort::receive(const EnergyPacket& packet) {
  if (packet.session < session_) {
    ++counters_.old_session_packets;
    return PacketVerdict::kStale;
  }
  if (packet.session > session_) {
    // the other end lost this one and started afresh: so does this end, or its totals (now
    // restarting from zero) would look like a decrease and be refused until they passed the old
    ++counters_.remote_restarts;
    start_session(packet.session);
  }
  return remote_.receive(packet);
}

void PassivityPort::start_session(std::uint32_t session) {
  session_ = session;
  remote_.reset();
  for (ChannelState& s : state_) {
    // what was dissipated stays dissipated: it is a report, not bookkeeping
    s = ChannelState{0.0, 0.0, s.dissipated_j, 0.0};
  }
  packet_.seq = 0;
  packet_.session = session;
  packet_.energy_in_j.fill(0.0);
  packet_.energy_out_j.fill(0.0);
}

}  // namespace teleop::control
