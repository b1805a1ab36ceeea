#pragma once
// A simulated two-channel position-force teleoperator at 1 kHz for the TDPA tests: per DOF a
// leader device pulled by a spring-damper "hand", a follower that tracks the integral of the
// received velocity with a stiff position spring, a stiff virtual wall, and a link that delays,
// jitters and drops each cycle's sample (signal + energy packet) in each direction.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "teleop/control/drift_compensation.h"
#include "teleop/control/passivity.h"

namespace teleop::control::test {

inline constexpr std::size_t kLoopDof = 2;
using DofArray = std::array<double, kLoopDof>;

/// One direction of the link.
struct LinkProfile {
  int delay_cycles = 50;
  /// Extra delay, uniform in 0..jitter_cycles per sample: samples overtake each other.
  int jitter_cycles = 0;
  /// Bernoulli loss probability per sample.
  double drop = 0.0;
  /// [first, last] cycles of sending during which every sample is lost.
  std::vector<std::pair<int, int>> bursts;
};

/// What crosses the link each cycle: the signal (velocity or force per DOF) and the sender's
/// energy packet, sent together.
struct LinkSample {
  std::uint64_t seq = 0;
  DofArray value{};
  EnergyPacket energy;
};

/// Delays and drops samples; seeded, so every run is the same.
class DelayLink {
 public:
  DelayLink(LinkProfile profile, std::uint32_t seed) : profile_(std::move(profile)), rng_(seed) {}

  void send(int cycle, const LinkSample& sample) {
    ++sent_;
    const bool burst = in_burst(cycle);
    const bool dropped = std::bernoulli_distribution(profile_.drop)(rng_);
    const int jitter = std::uniform_int_distribution<int>(0, profile_.jitter_cycles)(rng_);
    if (burst || dropped) {
      ++lost_;
      return;
    }
    in_flight_.push_back({cycle + profile_.delay_cycles + jitter, sample});
  }

  /// Calls `receive(sample)` for each sample due at `cycle`, in the order they were sent.
  template <typename F>
  void deliver(int cycle, F&& receive) {
    for (auto it = in_flight_.begin(); it != in_flight_.end();) {
      if (it->first <= cycle) {
        receive(it->second);
        it = in_flight_.erase(it);
      } else {
        ++it;
      }
    }
  }

  int sent() const { return sent_; }
  int lost() const { return lost_; }

 private:
  bool in_burst(int cycle) const {
    for (const auto& [first, last] : profile_.bursts) {
      if (cycle >= first && cycle <= last) {
        return true;
      }
    }
    return false;
  }

  LinkProfile profile_;
  std::mt19937 rng_;
  std::deque<std::pair<int, LinkSample>> in_flight_;
  int sent_ = 0;
  int lost_ = 0;
};

/// Plant and controller parameters. DOF 0 pushes into the wall and holds; DOF 1 moves freely
/// (its wall is out of reach) with a sinusoid on top of the same ramp.
struct LoopParams {
  double cycle_s = 0.001;
  int cycles = 4000;
  double leader_mass_kg = 1.0;
  double hand_stiffness_npm = 300.0;
  double hand_damping_nspm = 10.0;
  double follower_mass_kg = 1.0;
  double follower_damping_nspm = 20.0;
  double tracking_stiffness_npm = 3000.0;
  double wall_stiffness_npm = 30000.0;
  DofArray wall_m{0.05, 10.0};
  /// The hand's set point ramps from 0 to this in ramp_s, then holds.
  double hand_target_m = 0.1;
  double ramp_s = 1.0;
  double sine_amplitude_m = 0.03;
  double sine_hz = 1.0;
  bool controller_enabled = true;
  double max_damping = std::numeric_limits<double>::infinity();
  /// The follower's drift compensation (drift_compensation.h); 0: none.
  double drift_time_constant_s = 0.0;
  double drift_max_speed_mps = 0.1;
  LinkProfile leader_to_follower;
  LinkProfile follower_to_leader;
  std::uint32_t seed = 1;
};

/// Called every cycle after both ports' updates, to audit the run from outside.
struct CycleView {
  int cycle;
  const PassivityPort& leader;
  const PassivityPort& follower;
  /// Port inputs and corrected outputs of this cycle, in the ports' sign convention.
  const DofArray& leader_force;
  const DofArray& leader_velocity;
  const DofArray& leader_corrected_force;
  const DofArray& follower_force;
  const DofArray& follower_velocity;
  const DofArray& follower_corrected_velocity;
};

struct LoopResult {
  double leader_min_observed_j = 0.0;
  double follower_min_observed_j = 0.0;
  DofArray leader_dissipated_j{};
  DofArray follower_dissipated_j{};
  /// DOF 0: deepest wall penetration of the follower, and its peak-to-peak position over the
  /// last second (sustained oscillation).
  double max_penetration_m = 0.0;
  double late_peak_to_peak_m = 0.0;
  /// DOF 1: largest |x_F - x_L| over the run (free-motion tracking), and over the last second.
  double max_free_tracking_error_m = 0.0;
  double late_free_tracking_error_m = 0.0;
  /// The follower reference's drift per DOF at the end (drift_compensation.h).
  DofArray final_drift_m{};
  PassivityPort::Counters leader_counters;
  PassivityPort::Counters follower_counters;
  RemoteEnergy::Counters leader_packets;
  RemoteEnergy::Counters follower_packets;
  int samples_lost = 0;
};

template <typename Audit>
LoopResult run_loop(const LoopParams& p, Audit&& audit) {
  const double h = p.cycle_s;
  PassivityPortConfig config;
  config.channels = kLoopDof;
  config.cycle_s = h;
  config.controller_enabled = p.controller_enabled;
  config.max_damping = p.max_damping;
  config.causality = PortCausality::kForceOutput;
  PassivityPort leader(config);
  config.causality = PortCausality::kVelocityOutput;
  PassivityPort follower(config);
  DriftCompensationConfig drift_config;
  drift_config.channels = kLoopDof;
  drift_config.time_constant_s = p.drift_time_constant_s;
  drift_config.max_speed.fill(p.drift_max_speed_mps);
  DriftCompensator drift(drift_config);
  DelayLink to_follower(p.leader_to_follower, p.seed);
  DelayLink to_leader(p.follower_to_leader, p.seed + 1);

  DofArray x_l{}, v_l{}, x_f{}, v_f{}, x_d{};
  // newest signal received on each side (held when samples are lost)
  DofArray force_rx{}, velocity_rx{};
  std::uint64_t force_seq = 0, velocity_seq = 0;
  DofArray lf{}, lv{}, lf_out{}, ff{}, fv{}, fv_out{};
  LoopResult r;
  double late_min = 1e300, late_max = -1e300;
  for (int k = 0; k < p.cycles; ++k) {
    const double t = k * h;
    to_leader.deliver(k, [&](const LinkSample& s) {
      (void)leader.receive(s.energy);
      if (s.seq > force_seq) {
        force_seq = s.seq;
        force_rx = s.value;
      }
    });
    to_follower.deliver(k, [&](const LinkSample& s) {
      (void)follower.receive(s.energy);
      if (s.seq > velocity_seq) {
        velocity_seq = s.seq;
        velocity_rx = s.value;
      }
    });

    // leader port: the received follower force resists the device velocity
    lf = force_rx;
    lv = v_l;
    (void)leader.update(lf, lv, lf_out);
    // follower port: the tracking spring pulls the reference back with -f_track
    DofArray f_track{};
    for (std::size_t j = 0; j < kLoopDof; ++j) {
      f_track[j] = p.tracking_stiffness_npm * (x_d[j] - x_f[j]);
      ff[j] = -f_track[j];
    }
    for (std::size_t j = 0; j < kLoopDof; ++j) fv[j] = drift.request(j, velocity_rx[j], ff[j]);
    (void)follower.update(ff, fv, fv_out);
    for (std::size_t j = 0; j < kLoopDof; ++j) drift.account(j, velocity_rx[j], fv_out[j], h);
    audit(CycleView{k, leader, follower, lf, lv, lf_out, ff, fv, fv_out});

    LinkSample to_f{static_cast<std::uint64_t>(k + 1), v_l, leader.make_packet()};
    LinkSample to_l{static_cast<std::uint64_t>(k + 1), f_track, follower.make_packet()};
    to_follower.send(k, to_f);
    to_leader.send(k, to_l);

    // plants, semi-implicit Euler
    const double ramp = p.hand_target_m * std::min(1.0, t / p.ramp_s);
    for (std::size_t j = 0; j < kLoopDof; ++j) {
      const double sine = j == 1 ? p.sine_amplitude_m * std::sin(2.0 * 3.14159265358979 * p.sine_hz * t) : 0.0;
      const double f_hand = p.hand_stiffness_npm * (ramp + sine - x_l[j]) - p.hand_damping_nspm * v_l[j];
      v_l[j] += h * (f_hand - lf_out[j]) / p.leader_mass_kg;
      x_l[j] += h * v_l[j];
      x_d[j] += h * fv_out[j];
      const double penetration = x_f[j] - p.wall_m[j];
      const double f_wall = penetration > 0.0 ? -p.wall_stiffness_npm * penetration : 0.0;
      v_f[j] += h * (f_track[j] + f_wall - p.follower_damping_nspm * v_f[j]) / p.follower_mass_kg;
      x_f[j] += h * v_f[j];
    }
    r.max_penetration_m = std::max(r.max_penetration_m, x_f[0] - p.wall_m[0]);
    r.max_free_tracking_error_m = std::max(r.max_free_tracking_error_m, std::abs(x_f[1] - x_l[1]));
    if (k >= p.cycles - static_cast<int>(1.0 / h)) {
      r.late_free_tracking_error_m = std::max(r.late_free_tracking_error_m, std::abs(x_f[1] - x_l[1]));
      late_min = std::min(late_min, x_f[0]);
      late_max = std::max(late_max, x_f[0]);
    }
  }
  r.late_peak_to_peak_m = late_max - late_min;
  r.leader_min_observed_j = leader.min_observed_energy_j();
  r.follower_min_observed_j = follower.min_observed_energy_j();
  for (std::size_t j = 0; j < kLoopDof; ++j) {
    r.leader_dissipated_j[j] = leader.dissipated_energy_j(j);
    r.follower_dissipated_j[j] = follower.dissipated_energy_j(j);
    r.final_drift_m[j] = drift.drift(j);
  }
  r.leader_counters = leader.counters();
  r.follower_counters = follower.counters();
  r.leader_packets = leader.remote().counters();
  r.follower_packets = follower.remote().counters();
  r.samples_lost = to_follower.lost() + to_leader.lost();
  return r;
}

inline LoopResult run_loop(const LoopParams& p) {
  return run_loop(p, [](const CycleView&) {});
}

}  // namespace teleop::control::test
