#pragma once
// Passivity observer and passivity controller of one port of a two-channel teleoperator, the
// Time Domain Passivity Approach of Ryu & Preusche 2007 with energy packets (docs/tdpa.md).
//
// The communication channel (delay, loss, jitter) is a two-port between the leader (L) and the
// follower (F). Each port handles N independent channels (Cartesian axes or joints), each with
// a force-like f and a velocity-like v (N and m/s, or N m and rad/s).
//
// Sign convention, per channel and cycle k (h the cycle):
//   P_k = f_k v_k  [W]  is the power flowing INTO the channel at this port:
//     f = the force the local side exerts on the channel, v = the local side's velocity in the
//         same direction.
//   Leader (position-force): v = the device velocity sent to F, f = the feedback force the
//     channel delivers, taken as the force that resists v (the device renders -f).
//   Follower: v = the velocity command the channel delivers, f = the force the channel carries
//     back: the environment's force on the follower along v (a wall resisting v: f v < 0, the
//     channel delivers energy into the contact). The force-feedback estimate, not the controller's
//     own force: that also holds the energy that moves the follower's own mass, which the leader's
//     port never sees.
//   E_in  += max(0,  P_k) h    energy the local side put into the channel
//   E_out += max(0, -P_k) h    energy the channel delivered to the local side
// Each port sends its cumulative E_in to the other (energy_packets.h); the other one's E_in as
// last received, E_in^remote(k - D(k)) with any time-varying delay D, feeds the observer.
//
// Passivity observer (one direction of the energy flow: remote port -> this port):
//   W_k = E_in^remote(k - D(k)) - E_out_k  >= 0
// where E_out counts what actually left after the controller's correction, so the energy the
// controller dissipated is already accounted for (W = E_in^remote - E_out^uncorrected + E_diss).
//
// Passivity controller, in a cycle with outflow (P_k < 0): the observer with this cycle's
// uncorrected flow, W'_k = E_in^remote - E_out_{k-1} + P_k h, is negative by the deficit d_k =
// -W'_k. The controller dissipates exactly d_k with an adaptive damper on the quantity the channel
// delivers at this port:
//   force output    (leader, admittance / parallel type):  f_out = f + alpha v,
//                   alpha = d_k / (h v^2)   [N s/m]
//   velocity output (follower, impedance / series type):   v_out = v + beta f,
//                   beta  = d_k / (h f^2)   [m/(N s)]
// so P_out h = P_k h + d_k, W_k = 0, E_diss += d_k. Since W_{k-1} >= 0 and E_in^remote only
// grows, d_k <= -P_k h: the damper only ever reduces the outflow, never reverses it, and the
// corrected quantity lies between the original and zero (f_out = f (1 - d_k / (-P_k h))).
// A gain above `max_damping` is clamped (counted): the uncorrected part of the deficit stays in
// W < 0, and while it does the controller dissipates all further outflow (within the limit)
// until E_in^remote has grown past E_out again.
// Cycles without outflow need no correction: W cannot drop in them.
//
// update() and receive() are real-time safe: no allocation, no exception, status codes.

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>

#include "teleop/control/energy_packets.h"

namespace teleop::control {

/// The quantity the channel delivers at this port, which the passivity controller corrects.
enum class PortCausality {
  /// The channel delivers a force (the leader of a position-force teleoperator): f_out = f + alpha v.
  kForceOutput,
  /// The channel delivers a velocity (the follower): v_out = v + beta f.
  kVelocityOutput,
};

struct PassivityPortConfig {
  /// Independent channels, 1..kMaxTdpaChannels.
  std::size_t channels = 0;
  /// Cycle h [s] of update(), > 0.
  double cycle_s = 0.001;
  PortCausality causality = PortCausality::kForceOutput;
  /// false: observe only (W is computed and may go negative, nothing is corrected); the
  /// bilateral controller without TDPA reports its energy balance this way.
  bool controller_enabled = true;
  /// Limit of alpha [N s/m or N m s/rad] or beta [m/(N s) or rad/(N m s)], > 0; infinity: none.
  double max_damping = std::numeric_limits<double>::infinity();
};

/// Outcome of one update(), the most severe first.
enum class PortStatus {
  kOk,
  /// A damper gain was clamped at max_damping in some channel: W < 0 remains there.
  kSaturated,
  /// Some channel's f or v was NaN/Inf: its corrected output is 0, its power counted as 0.
  kNonFiniteInput,
  /// A span's size differs from `channels`: nothing was computed, outputs untouched.
  kSizeMismatch,
};

/// One port of the channel: energy bookkeeping, passivity observer, passivity controller.
class PassivityPort {
 public:
  struct Counters {
    std::uint64_t cycles = 0;
    /// Channel-cycles with a deficit (W' < 0), corrected or (observe only) not.
    std::uint64_t deficits = 0;
    /// Channel-cycles whose damper gain was clamped.
    std::uint64_t saturations = 0;
    /// Channel-cycles with a non-finite f or v.
    std::uint64_t non_finite_inputs = 0;
    /// update() calls rejected for a span of the wrong size.
    std::uint64_t size_mismatches = 0;
    /// Sessions the other end started (its packets' newer session restarted this end).
    std::uint64_t remote_restarts = 0;
    /// Packets of a session this end has left (in flight across a reset): ignored.
    std::uint64_t old_session_packets = 0;
  };

  /// Throws std::invalid_argument naming the bad field.
  explicit PassivityPort(const PassivityPortConfig& config);

  /// An energy packet from the other port (any rate, any order; see RemoteEnergy). A packet of a
  /// newer session than this end's restarts this end first (both ends always reset together,
  /// whichever noticed the loss); one of an older session is ignored as kStale.
  [[nodiscard]] PacketVerdict receive(const EnergyPacket& packet);

  /// One cycle: `force` and `velocity` per channel in the sign convention above; writes the
  /// corrected output (force or velocity by causality) to `corrected`, which may alias the
  /// corresponding input.
  [[nodiscard]] PortStatus update(std::span<const double> force, std::span<const double> velocity,
                                  std::span<double> corrected);

  /// The packet to send after this cycle's update(): this port's totals, the next sequence number.
  const EnergyPacket& make_packet();

  /// This end starts a new session (it lost the other end): energies and sequence numbers back
  /// to zero; its next packet tells the other end to do the same. Counters are kept.
  void reset() { start_session(session_ + 1); }
  /// The session this end is in (0 until a reset on either end).
  std::uint32_t session() const { return session_; }

  /// W [J] of `channel` after the last update: E_in^remote - E_out.
  double observed_energy_j(std::size_t channel) const { return remote_.energy_in_j(channel) - state_[channel].out_j; }
  /// The smallest W [J] of any channel after any update, over all sessions (0 before the first).
  double min_observed_energy_j() const { return min_observed_j_; }
  double energy_in_j(std::size_t channel) const { return state_[channel].in_j; }
  double energy_out_j(std::size_t channel) const { return state_[channel].out_j; }
  /// Energy [J] the controller has dissipated on `channel`.
  double dissipated_energy_j(std::size_t channel) const { return state_[channel].dissipated_j; }
  /// The damper gain (alpha or beta) of the last update; 0 when inactive.
  double damping(std::size_t channel) const { return state_[channel].damping; }
  double remote_energy_in_j(std::size_t channel) const { return remote_.energy_in_j(channel); }
  const RemoteEnergy& remote() const { return remote_; }
  const Counters& counters() const { return counters_; }
  const PassivityPortConfig& config() const { return config_; }

 private:
  struct ChannelState {
    double in_j = 0.0;
    double out_j = 0.0;
    double dissipated_j = 0.0;
    double damping = 0.0;
  };

  /// One channel's bookkeeping and correction; returns the corrected output. Sets `saturated`.
  double update_channel(std::size_t i, double f, double v, bool& saturated);
  /// Energies, the remote totals and the packet numbering back to zero, in `session`.
  void start_session(std::uint32_t session);

  PassivityPortConfig config_;
  RemoteEnergy remote_;
  std::array<ChannelState, kMaxTdpaChannels> state_{};
  double min_observed_j_ = 0.0;
  EnergyPacket packet_;
  Counters counters_;
  std::uint32_t session_ = 0;
};

}  // namespace teleop::control
