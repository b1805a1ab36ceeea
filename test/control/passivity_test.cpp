#include "teleop/control/passivity.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "allocation_counter.h"
#include "tdpa_test_loop.h"
#include "test_helpers.h"

namespace teleop::control {
namespace {

using test::kLoopDof;
using test::LoopParams;

constexpr double kH = 0.001;

PassivityPortConfig one_channel(PortCausality causality) {
  PassivityPortConfig c;
  c.channels = 1;
  c.cycle_s = kH;
  c.causality = causality;
  return c;
}

// The other side announces `in_j` joules of input energy.
void grant(PassivityPort& port, std::uint64_t seq, double in_j) {
  EnergyPacket p;
  p.seq = seq;
  p.channels = port.config().channels;
  p.energy_in_j.fill(in_j);
  ASSERT_EQ(port.receive(p), PacketVerdict::kAccepted);
}

// Runs one cycle of a 1-channel port; returns the corrected output.
double step(PassivityPort& port, double f, double v, PortStatus expected = PortStatus::kOk) {
  std::array<double, 1> force{f}, velocity{v}, out{};
  EXPECT_EQ(port.update(force, velocity, out), expected);
  return out[0];
}

TEST(PassivityPort, ForceOutputAddsTheDamperThatDissipatesTheDeficit) {
  PassivityPort port(one_channel(PortCausality::kForceOutput));
  grant(port, 1, 1e-3);
  // f v = -2 W: 2 mJ would leave in this cycle, 1 mJ came in; alpha = 1e-3 / (h v^2) = 1 N s/m
  const double f_out = step(port, -2.0, 1.0);
  EXPECT_DOUBLE_EQ(port.damping(0), 1.0);
  EXPECT_DOUBLE_EQ(f_out, -2.0 + 1.0 * 1.0);
  EXPECT_DOUBLE_EQ(port.dissipated_energy_j(0), 1e-3);
  EXPECT_EQ(port.observed_energy_j(0), 0.0);
  EXPECT_EQ(port.energy_out_j(0), 1e-3);
  // no energy left: the whole next outflow is dissipated, the output goes to zero
  EXPECT_EQ(step(port, -2.0, 1.0), 0.0);
  EXPECT_DOUBLE_EQ(port.dissipated_energy_j(0), 3e-3);
  // inflow needs no correction and counts as input
  EXPECT_EQ(step(port, 2.0, 1.0), 2.0);
  EXPECT_DOUBLE_EQ(port.energy_in_j(0), 2e-3);
  EXPECT_EQ(port.counters().deficits, 2u);
}

TEST(PassivityPort, VelocityOutputAddsTheSeriesDamperThatDissipatesTheDeficit) {
  PassivityPort port(one_channel(PortCausality::kVelocityOutput));
  grant(port, 1, 3e-3);
  // f v = -4 W (f = -2 N, v = 2 m/s): 4 mJ out, 3 mJ in; beta = 1e-3 / (h f^2) = 0.25 m/(N s)
  const double v_out = step(port, -2.0, 2.0);
  EXPECT_DOUBLE_EQ(port.damping(0), 0.25);
  EXPECT_DOUBLE_EQ(v_out, 2.0 + 0.25 * -2.0);
  EXPECT_DOUBLE_EQ(port.dissipated_energy_j(0), 1e-3);
  EXPECT_EQ(port.observed_energy_j(0), 0.0);
}

TEST(PassivityPort, PassesTheOutflowTheObservedEnergyCovers) {
  PassivityPort port(one_channel(PortCausality::kVelocityOutput));
  grant(port, 1, 1.0);
  EXPECT_EQ(step(port, -2.0, 2.0), 2.0);
  EXPECT_DOUBLE_EQ(port.observed_energy_j(0), 1.0 - 4e-3);
  EXPECT_EQ(port.dissipated_energy_j(0), 0.0);
  EXPECT_EQ(port.damping(0), 0.0);
  EXPECT_EQ(port.counters().deficits, 0u);
}

TEST(PassivityPort, ClampsTheGainCountsItAndCarriesTheDeficit) {
  auto config = one_channel(PortCausality::kForceOutput);
  config.max_damping = 0.5;
  PassivityPort port(config);
  grant(port, 1, 1e-3);
  // alpha would be 1 N s/m: clamped to 0.5, dissipating 0.5 mJ of the 1 mJ deficit
  EXPECT_DOUBLE_EQ(step(port, -2.0, 1.0, PortStatus::kSaturated), -1.5);
  EXPECT_DOUBLE_EQ(port.observed_energy_j(0), -0.5e-3);
  EXPECT_DOUBLE_EQ(port.dissipated_energy_j(0), 0.5e-3);
  // a small outflow while W < 0 is dissipated in full (alpha 0.25 within the limit)
  EXPECT_EQ(step(port, -0.25, 1.0), 0.0);
  EXPECT_DOUBLE_EQ(port.observed_energy_j(0), -0.5e-3);
  // the other side's input covers the carried deficit again
  grant(port, 2, 2e-3);
  EXPECT_DOUBLE_EQ(port.observed_energy_j(0), 0.5e-3);
  EXPECT_EQ(port.counters().saturations, 1u);
  EXPECT_EQ(port.counters().deficits, 2u);
}

TEST(PassivityPort, ObserveOnlyLetsTheObservedEnergyGoNegative) {
  auto config = one_channel(PortCausality::kForceOutput);
  config.controller_enabled = false;
  PassivityPort port(config);
  EXPECT_EQ(step(port, -2.0, 1.0), -2.0);
  EXPECT_DOUBLE_EQ(port.observed_energy_j(0), -2e-3);
  EXPECT_DOUBLE_EQ(port.min_observed_energy_j(), -2e-3);
  EXPECT_EQ(port.dissipated_energy_j(0), 0.0);
  EXPECT_EQ(port.counters().deficits, 1u);
}

TEST(PassivityPort, ZeroesANonFiniteChannelAndCountsIt) {
  PassivityPortConfig config = one_channel(PortCausality::kVelocityOutput);
  config.channels = 2;
  PassivityPort port(config);
  grant(port, 1, 1.0);
  std::array<double, 2> force{std::nan(""), -1.0}, velocity{1.0, 1.0}, out{};
  EXPECT_EQ(port.update(force, velocity, out), PortStatus::kNonFiniteInput);
  EXPECT_EQ(out[0], 0.0);
  EXPECT_EQ(out[1], 1.0);
  EXPECT_EQ(port.energy_out_j(0), 0.0);
  EXPECT_DOUBLE_EQ(port.energy_out_j(1), 1e-3);
  EXPECT_EQ(port.counters().non_finite_inputs, 1u);
}

TEST(PassivityPort, RejectsSpansOfTheWrongSizeWithoutTouchingThem) {
  PassivityPort port(one_channel(PortCausality::kForceOutput));
  std::array<double, 2> force{-1.0, -1.0}, velocity{1.0, 1.0}, out{7.0, 7.0};
  EXPECT_EQ(port.update(force, velocity, out), PortStatus::kSizeMismatch);
  EXPECT_EQ(out[0], 7.0);
  EXPECT_EQ(port.counters().size_mismatches, 1u);
  EXPECT_EQ(port.counters().cycles, 0u);
}

TEST(PassivityPort, PacketsCarryCumulativeTotalsWithConsecutiveSequenceNumbers) {
  PassivityPort port(one_channel(PortCausality::kForceOutput));
  (void)step(port, 1.0, 1.0);
  EXPECT_EQ(port.make_packet().seq, 1u);
  (void)step(port, 3.0, 1.0);
  const EnergyPacket& p = port.make_packet();
  EXPECT_EQ(p.seq, 2u);
  EXPECT_EQ(p.channels, 1u);
  EXPECT_DOUBLE_EQ(p.energy_in_j[0], 4e-3);
  port.reset();
  const EnergyPacket& after = port.make_packet();
  EXPECT_EQ(after.seq, 1u);
  EXPECT_EQ(after.session, 1u);
  EXPECT_EQ(port.energy_in_j(0), 0.0);
}

TEST(PassivityPort, AnEndThatRestartsRestartsTheOtherEndWithIt) {
  PassivityPort leader(one_channel(PortCausality::kForceOutput));
  PassivityPort follower(one_channel(PortCausality::kVelocityOutput));
  // a session's worth of energy both ways
  (void)step(leader, 2.0, 1.0);
  (void)step(follower, 2.0, 1.0);
  ASSERT_EQ(follower.receive(leader.make_packet()), PacketVerdict::kAccepted);
  ASSERT_EQ(leader.receive(follower.make_packet()), PacketVerdict::kAccepted);
  EXPECT_GT(leader.remote_energy_in_j(0), 0.0);
  // the follower lost the leader for a moment and starts afresh
  follower.reset();
  // a leader packet sent before the leader heard of it is from the old session: ignored
  (void)step(leader, 2.0, 1.0);
  EXPECT_EQ(follower.receive(leader.make_packet()), PacketVerdict::kStale);
  EXPECT_EQ(follower.remote_energy_in_j(0), 0.0);
  EXPECT_EQ(follower.counters().old_session_packets, 1u);
  // the follower's first packet of the new session carries small totals: accepted, and the
  // leader restarts its own bookkeeping instead of refusing them as a decrease
  (void)step(follower, 1.0, 1.0);
  EXPECT_EQ(leader.receive(follower.make_packet()), PacketVerdict::kAccepted);
  EXPECT_EQ(leader.session(), 1u);
  EXPECT_EQ(leader.counters().remote_restarts, 1u);
  EXPECT_EQ(leader.energy_in_j(0), 0.0);
  EXPECT_DOUBLE_EQ(leader.remote_energy_in_j(0), 1e-3);
  EXPECT_EQ(leader.remote().counters().invalid, 0u);
  // and from now on both count the same session
  (void)step(leader, 3.0, 1.0);
  const EnergyPacket& p = leader.make_packet();
  EXPECT_EQ(p.session, 1u);
  EXPECT_EQ(p.seq, 1u);
  EXPECT_EQ(follower.receive(p), PacketVerdict::kAccepted);
  EXPECT_DOUBLE_EQ(follower.remote_energy_in_j(0), 3e-3);
}

TEST(PassivityPort, RejectsBadConfigurationNamingTheField) {
  auto config = one_channel(PortCausality::kForceOutput);
  config.cycle_s = 0.0;
  EXPECT_NE(teleop::test::error_of<std::invalid_argument>([&] { PassivityPort p(config); }).find("cycle_s"),
            std::string::npos);
  config = one_channel(PortCausality::kForceOutput);
  config.max_damping = -1.0;
  EXPECT_NE(teleop::test::error_of<std::invalid_argument>([&] { PassivityPort p(config); }).find("max_damping"),
            std::string::npos);
  config = one_channel(PortCausality::kForceOutput);
  config.channels = 17;
  EXPECT_NE(teleop::test::error_of<std::invalid_argument>([&] {
              PassivityPort p(config);
            }).find("PassivityPortConfig.channels"),
            std::string::npos);
}

// A delayed position-force loop around a stiff wall (tdpa_test_loop.h), 50 cycles each way.
TEST(PassivityPort, ObserverGoesNegativeUnderDelayWithoutTheControllerAndNeverWithIt) {
  LoopParams p;
  p.controller_enabled = false;
  // without the controller: when the follower's observer first drops below zero, and its value
  // after the first second (before the loop has grown large)
  int first_negative_cycle = -1;
  double w_after_1s = 0.0;
  const auto open = test::run_loop(p, [&](const test::CycleView& c) {
    if (first_negative_cycle < 0 && c.follower.observed_energy_j(0) < 0.0) {
      first_negative_cycle = c.cycle;
    }
    if (c.cycle == 1000) {
      w_after_1s = c.follower.observed_energy_j(0);
    }
  });
  p.controller_enabled = true;
  double min_w = 0.0;
  const auto closed = test::run_loop(p, [&](const test::CycleView& c) {
    for (std::size_t j = 0; j < kLoopDof; ++j) {
      min_w = std::min({min_w, c.leader.observed_energy_j(j), c.follower.observed_energy_j(j)});
    }
  });
  std::printf(
      "50+50 cycle delay, stiff wall, without PC: follower W < 0 first at cycle %d, W = %.4g J at 1 s; "
      "min W over 4 s leader %.3g J, follower %.3g J; last-second peak-to-peak %.3g m; free-DOF "
      "tracking error %.4g m\n",
      first_negative_cycle, w_after_1s, open.leader_min_observed_j, open.follower_min_observed_j,
      open.late_peak_to_peak_m, open.max_free_tracking_error_m);
  std::printf(
      "  with PC: min W %.3g J, dissipated leader %.4g/%.4g J, follower %.4g/%.4g J (wall/free DOF), "
      "penetration %.4g m, last-second peak-to-peak %.4g m, free-DOF tracking error %.4g m, deficit "
      "channel-cycles L %llu F %llu\n",
      min_w, closed.leader_dissipated_j[0], closed.leader_dissipated_j[1], closed.follower_dissipated_j[0],
      closed.follower_dissipated_j[1], closed.max_penetration_m, closed.late_peak_to_peak_m,
      closed.max_free_tracking_error_m, static_cast<unsigned long long>(closed.leader_counters.deficits),
      static_cast<unsigned long long>(closed.follower_counters.deficits));
  EXPECT_GE(first_negative_cycle, 0);
  EXPECT_LT(open.follower_min_observed_j, -1e-3);
  EXPECT_LT(open.leader_min_observed_j, -1e-3);
  EXPECT_GE(min_w, 0.0);
  EXPECT_GE(closed.leader_min_observed_j, 0.0);
  EXPECT_GE(closed.follower_min_observed_j, 0.0);
  EXPECT_EQ(closed.leader_counters.saturations + closed.follower_counters.saturations, 0u);
  // this plant: without the controller the contact oscillation grows without bound, with it the
  // follower reaches the wall and comes to rest there
  EXPECT_GT(open.late_peak_to_peak_m, 1.0);
  EXPECT_GT(closed.follower_dissipated_j[0], 0.0);
  EXPECT_GT(closed.max_penetration_m, 0.0);
  EXPECT_LT(closed.late_peak_to_peak_m, 1e-3);
}

LoopParams lossy_loop() {
  LoopParams p;
  for (auto* link : {&p.leader_to_follower, &p.follower_to_leader}) {
    link->delay_cycles = 50;
    link->jitter_cycles = 10;
    link->drop = 0.2;
  }
  p.leader_to_follower.bursts = {{700, 850}, {2000, 2100}};
  p.follower_to_leader.bursts = {{1200, 1400}, {3000, 3050}};
  p.seed = 42;
  return p;
}

TEST(PassivityPort, KeepsTheBalanceWithDroppedPacketsBurstsAndReordering) {
  const LoopParams p = lossy_loop();
  // each port's input totals as sent in packet seq (= cycle + 1)
  std::vector<std::array<double, kLoopDof>> leader_sent(p.cycles + 1), follower_sent(p.cycles + 1);
  int mismatches = 0;
  double min_w = 0.0;
  const auto r = test::run_loop(p, [&](const test::CycleView& c) {
    for (std::size_t j = 0; j < kLoopDof; ++j) {
      leader_sent[c.cycle + 1][j] = c.leader.energy_in_j(j);
      follower_sent[c.cycle + 1][j] = c.follower.energy_in_j(j);
      // the receiver knows exactly the totals of the last packet it accepted, nothing else
      mismatches += c.leader.remote_energy_in_j(j) != follower_sent[c.leader.remote().last_seq()][j];
      mismatches += c.follower.remote_energy_in_j(j) != leader_sent[c.follower.remote().last_seq()][j];
      min_w = std::min({min_w, c.leader.observed_energy_j(j), c.follower.observed_energy_j(j)});
    }
  });
  std::printf(
      "20%% loss + bursts, 50-60 cycle delay: %d of %d samples lost; leader used %llu packets "
      "(%llu missed, %llu stale), follower %llu (%llu missed, %llu stale); min W %.3g J, "
      "dissipated leader %.4g J, follower %.4g J, penetration %.4g m\n",
      r.samples_lost, 2 * p.cycles, static_cast<unsigned long long>(r.leader_packets.accepted),
      static_cast<unsigned long long>(r.leader_packets.missed), static_cast<unsigned long long>(r.leader_packets.stale),
      static_cast<unsigned long long>(r.follower_packets.accepted),
      static_cast<unsigned long long>(r.follower_packets.missed),
      static_cast<unsigned long long>(r.follower_packets.stale), min_w,
      r.leader_dissipated_j[0] + r.leader_dissipated_j[1], r.follower_dissipated_j[0] + r.follower_dissipated_j[1],
      r.max_penetration_m);
  EXPECT_EQ(mismatches, 0);
  EXPECT_GE(min_w, 0.0);
  // the run really lost, reordered and bridged packets
  EXPECT_GT(r.samples_lost, p.cycles / 5);
  EXPECT_GT(r.leader_packets.missed, 200u);
  EXPECT_GT(r.follower_packets.missed, 200u);
  EXPECT_GT(r.leader_packets.stale + r.follower_packets.stale, 0u);
  EXPECT_EQ(r.leader_packets.invalid + r.follower_packets.invalid, 0u);
}

// Audits one port from outside: its own integrals of the flows before and after correction.
struct PortAudit {
  std::array<double, kLoopDof> out_j{};      // E_out of the corrected flow
  std::array<double, kLoopDof> deficit_j{};  // sum of -W' where W' < 0
  std::array<double, kLoopDof> drained_j{};  // sum of (P_corrected - P) h

  void cycle(const PassivityPort& port, const test::DofArray& f, const test::DofArray& v, const test::DofArray& f_out,
             const test::DofArray& v_out) {
    for (std::size_t j = 0; j < kLoopDof; ++j) {
      const double p = f[j] * v[j];
      const double p_out = f_out[j] * v_out[j];
      const double w_before = port.remote_energy_in_j(j) - out_j[j] - std::max(0.0, -p * kH);
      deficit_j[j] += std::max(0.0, -w_before);
      drained_j[j] += (p_out - p) * kH;
      out_j[j] += std::max(0.0, -p_out * kH);
    }
  }
};

TEST(PassivityPort, DissipatesExactlyTheDeficitItCorrects) {
  const LoopParams p = lossy_loop();
  PortAudit leader, follower;
  const auto r = test::run_loop(p, [&](const test::CycleView& c) {
    leader.cycle(c.leader, c.leader_force, c.leader_velocity, c.leader_corrected_force, c.leader_velocity);
    follower.cycle(c.follower, c.follower_force, c.follower_velocity, c.follower_force, c.follower_corrected_velocity);
  });
  ASSERT_EQ(r.leader_counters.saturations + r.follower_counters.saturations, 0u);
  double worst = 0.0;
  for (std::size_t j = 0; j < kLoopDof; ++j) {
    for (const auto& [audit, dissipated] :
         {std::pair{&leader, r.leader_dissipated_j[j]}, std::pair{&follower, r.follower_dissipated_j[j]}}) {
      EXPECT_GT(dissipated, 0.0);
      EXPECT_NEAR(audit->deficit_j[j], dissipated, 1e-9);
      EXPECT_NEAR(audit->drained_j[j], dissipated, 1e-9);
      worst = std::max({worst, std::abs(audit->deficit_j[j] - dissipated), std::abs(audit->drained_j[j] - dissipated)});
    }
  }
  std::printf(
      "dissipated vs corrected deficit vs drained by the damper: worst difference %.3g J over %zu "
      "channels and both ports\n",
      worst, kLoopDof);
}

TEST(PassivityPort, UpdateReceiveAndPacketsDoNotAllocate) {
  PassivityPortConfig config;
  config.channels = 7;
  config.cycle_s = kH;
  config.causality = PortCausality::kVelocityOutput;
  PassivityPort port(config);
  config.causality = PortCausality::kForceOutput;
  PassivityPort other(config);
  std::array<double, 7> f{}, v{}, out{};
  teleop::test::ScopedAllocationCounter counter;
  for (int k = 0; k < 1000; ++k) {
    for (std::size_t j = 0; j < 7; ++j) {
      f[j] = std::sin(0.01 * k + static_cast<double>(j));
      v[j] = std::cos(0.013 * k);
    }
    (void)port.update(f, v, out);
    (void)other.update(f, v, out);
    if (k % 3 == 0) {
      (void)port.receive(other.make_packet());
      (void)other.receive(port.make_packet());
    }
  }
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_GT(port.counters().deficits, 0u);
  EXPECT_GT(port.dissipated_energy_j(0), 0.0);
}

}  // namespace
}  // namespace teleop::control
