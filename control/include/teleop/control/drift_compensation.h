#pragma once
// Position drift compensation for the velocity-output (follower) port of TDPA (docs/tdpa.md,
// "Drift compensation").
//
// The follower's passivity controller slows the velocity the channel delivers (v_out = v + beta f).
// A reference that integrates v_out then lags the one the leader meant, and the lag -- the drift
// d = integral of (v_out - v) -- stays: in a box task the hands never reach the box. The
// compensator asks for the drift back, gently, by requesting
//     v_req = v - clamp(d / tau, -max_speed, +max_speed)
// from the passivity controller instead of v. The controller passes the request only as far as
// the observed energy covers it, so the return costs no passivity: the drift comes back when the
// channel has energy to spare (W > 0) and waits while it has none. The drift is always measured
// against the uncompensated v, so what the compensation returns is taken off it.
//
// Never into a contact: while a channel's port force (the environment's push on the robot) is
// above its contact threshold, a return against that push waits (one away from it goes on). In
// contact the operator controls a force, not a position; returning the drift into it spends the
// observed energy on pressing harder than before, and leaves the leader none to render the rise
// (docs/tdpa.md, "Drift compensation").
//
// request() and account() are real-time safe.

#include <array>
#include <cstddef>
#include <limits>

#include "teleop/control/energy_packets.h"

namespace teleop::control {

struct DriftCompensationConfig {
  /// Channels, 1..kMaxTdpaChannels.
  std::size_t channels = 0;
  /// tau [s] with which the drift is asked back; 0: no compensation (the drift is still tracked).
  double time_constant_s = 0.0;
  /// Largest compensating speed per channel (m/s or rad/s), > 0; infinity: none.
  std::array<double, kMaxTdpaChannels> max_speed{};
  /// |port force| (N or N m) above which a channel is in contact: a return against the force
  /// waits, > 0; infinity: always compensate.
  std::array<double, kMaxTdpaChannels> contact_force = filled(std::numeric_limits<double>::infinity());

 private:
  static std::array<double, kMaxTdpaChannels> filled(double value) {
    std::array<double, kMaxTdpaChannels> a;
    a.fill(value);
    return a;
  }
};

class DriftCompensator {
 public:
  /// Throws std::invalid_argument naming the bad field.
  explicit DriftCompensator(const DriftCompensationConfig& config);

  /// The velocity to hand to the passivity controller in place of the received `v` on `channel`,
  /// whose port force is `f` (v itself while a return would press into a contact).
  double request(std::size_t channel, double v, double f) const;
  /// After the controller: the received `v`, what it let through `v_out`, over one cycle `h_s`.
  void account(std::size_t channel, double v, double v_out, double h_s) {
    drift_[channel] += (v_out - v) * h_s;
  }
  /// The reference's offset from the leader's [m or rad]: integral of (v_out - v).
  double drift(std::size_t channel) const { return drift_[channel]; }
  void reset() { drift_.fill(0.0); }

  const DriftCompensationConfig& config() const { return config_; }

 private:
  DriftCompensationConfig config_;
  std::array<double, kMaxTdpaChannels> drift_{};
};

}  // namespace teleop::control
