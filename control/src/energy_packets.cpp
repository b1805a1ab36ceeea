#include "teleop/control/energy_packets.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace teleop::control {

RemoteEnergy::RemoteEnergy(std::size_t channels) : channels_(channels) {
  if (channels == 0 || channels > kMaxTdpaChannels) {
    throw std::invalid_argument("RemoteEnergy: channels must be 1.." + std::to_string(kMaxTdpaChannels) + ", got " +
                                std::to_string(channels));
  }
}

bool RemoteEnergy::valid(const EnergyPacket& packet) const {
  if (packet.channels != channels_ || packet.seq == 0) {
    return false;
  }
  for (std::size_t i = 0; i < channels_; ++i) {
    const double in = packet.energy_in_j[i];
    const double out = packet.energy_out_j[i];
    if (!std::isfinite(in) || !std::isfinite(out) || in < 0.0 || out < 0.0 || in < energy_in_j_[i]) {
      return false;
    }
  }
  return true;
}

PacketVerdict RemoteEnergy::receive(const EnergyPacket& packet) {
  // staleness first: an old packet may legitimately hold totals below the accepted ones
  if (packet.seq != 0 && packet.seq <= last_seq_) {
    ++counters_.stale;
    return PacketVerdict::kStale;
  }
  if (!valid(packet)) {
    ++counters_.invalid;
    return PacketVerdict::kInvalid;
  }
  // the first packet after a reset: the sender's numbers before it belong to another session
  if (last_seq_ != 0) counters_.missed += packet.seq - last_seq_ - 1;
  ++counters_.accepted;
  last_seq_ = packet.seq;
  for (std::size_t i = 0; i < channels_; ++i) {
    energy_in_j_[i] = packet.energy_in_j[i];
  }
  return PacketVerdict::kAccepted;
}

void RemoteEnergy::reset() {
  last_seq_ = 0;
  energy_in_j_.fill(0.0);
  counters_ = Counters{};
}

}  // namespace teleop::control
