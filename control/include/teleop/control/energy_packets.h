#pragma once
// Energy packets of the Time Domain Passivity Approach (Ryu & Preusche 2007, docs/tdpa.md): what
// one port of the communication channel tells the other about the energy that entered it.
//
// Every packet carries cumulative totals since the session start, never increments, so a lost
// packet loses no energy: the next one that arrives carries it. A packet whose sequence number
// is not newer than the last accepted one (duplicate, reordered) is ignored. Delay only means the
// receiver works with an older, smaller total, which is the conservative side.
// receive() is real-time safe: no allocation, no exception.

#include <array>
#include <cstddef>
#include <cstdint>

namespace teleop::control {

/// Channels (DOFs) a TDPA port handles at most; equals msg::MAX_TDPA_CHANNELS (idl/arm.idl).
inline constexpr std::size_t kMaxTdpaChannels = 16;

/// Cumulative energies [J] of one port since its reset. On the bus this is msg::TdpaEnergy:
/// `seq` is header.seq, the arrays fill the sequences of the same name up to `channels`.
struct EnergyPacket {
  /// Per-sender sequence number, first packet 1.
  std::uint64_t seq = 0;
  /// The sender's session (PassivityPort::reset): a newer one than the receiver's restarts the
  /// receiver's bookkeeping too, an older one is a packet still in flight from before.
  std::uint32_t session = 0;
  std::size_t channels = 0;
  /// Energy that entered the channel at the sender's port (power f v > 0), per channel.
  std::array<double, kMaxTdpaChannels> energy_in_j{};
  /// Energy that left the channel at the sender's port (power f v < 0), per channel; for
  /// monitoring, the receiver's observer does not use it.
  std::array<double, kMaxTdpaChannels> energy_out_j{};
};

/// What receive() did with a packet.
enum class PacketVerdict {
  kAccepted,
  /// Sequence number not newer than the last accepted one (duplicate or reordered): ignored.
  kStale,
  /// Wrong channel count, seq 0, a non-finite or negative energy, or an input total smaller
  /// than the accepted one (totals never decrease within a session): ignored and counted.
  kInvalid,
};

/// The other port's cumulative input energy as known here: the totals of the newest valid packet.
class RemoteEnergy {
 public:
  struct Counters {
    std::uint64_t accepted = 0;
    std::uint64_t stale = 0;
    std::uint64_t invalid = 0;
    /// Sequence numbers skipped between accepted packets: packets never used (lost, or arrived
    /// after a newer one). Counted from the first packet accepted after a reset.
    std::uint64_t missed = 0;
  };

  /// `channels` in 1..kMaxTdpaChannels; throws std::invalid_argument otherwise.
  explicit RemoteEnergy(std::size_t channels);

  /// Takes the totals of `packet` when it is valid and newer than the last accepted one.
  [[nodiscard]] PacketVerdict receive(const EnergyPacket& packet);

  /// Forgets everything received (new session: the other side resets too).
  void reset();

  /// The other side's input energy [J] on `channel` (< channels()) as of the last accepted packet;
  /// 0 before the first.
  double energy_in_j(std::size_t channel) const { return energy_in_j_[channel]; }
  /// Sequence number of the last accepted packet; 0 before the first.
  std::uint64_t last_seq() const { return last_seq_; }
  std::size_t channels() const { return channels_; }
  const Counters& counters() const { return counters_; }

 private:
  bool valid(const EnergyPacket& packet) const;

  std::size_t channels_;
  std::uint64_t last_seq_ = 0;
  std::array<double, kMaxTdpaChannels> energy_in_j_{};
  Counters counters_;
};

}  // namespace teleop::control
