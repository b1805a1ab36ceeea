#pragma once
// One end of the TDPA channel on the bus: a PassivityPort (control/passivity.h) whose energy
// packets travel as msg::TdpaEnergy on teleop/tdpa/{leader_to_follower, follower_to_leader}.
// The leader's end corrects the force it renders, the follower's the velocity it tracks.
// Each cycle: receive() the newest packet, update() with this cycle's force and velocity, then
// publish() this end's cumulative totals. Everything after construction is real-time safe.

#include <teleop/msg/status.h>

#include <limits>
#include <span>
#include <string>

#include "teleop/control/passivity.h"
#include "teleop/runtime/node_report.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/publication.h"
#include "teleop/transport/subscription.h"

namespace teleop::runtime {

enum class TdpaEnd { kLeader, kFollower };

class TdpaLink {
 public:
  /// `controller_enabled` false: observe the energy balance only (pfc without TDPA reports it).
  /// `arm`: whose channel on a multi-arm robot ("" for a one-arm robot; transport/arm_topic.h).
  TdpaLink(transport::Participant& participant, const std::string& node_name, const std::string& arm, TdpaEnd end,
           std::size_t channels, double cycle_s, bool controller_enabled, double max_damping);

  /// Takes the newest packet from the other end, if one arrived.
  void receive();
  /// This cycle's bookkeeping and correction (see PassivityPort::update).
  control::PortStatus update(std::span<const double> force, std::span<const double> velocity,
                             std::span<double> corrected);
  /// Sends this end's totals.
  void publish();
  /// This end lost the other one: a new session, energies back to zero; the other end follows
  /// when it receives this end's next packet (PassivityPort::receive).
  void reset() { port_.reset(); }

  const control::PassivityPort& port() const { return port_; }
  /// The smallest observed energy over the channels after the last update [J].
  double observed_energy_j() const;
  /// The energy the passivity controller has dissipated so far, over the channels [J].
  double dissipated_energy_j() const;
  /// Whether the controller acted in the last update (a damper on in some channel).
  bool acting() const;
  void fill_report(runtime::NodeReport& report) const;

 private:
  control::PassivityPort port_;
  transport::Publication<msg::TdpaEnergy> out_;
  transport::Subscription<msg::TdpaEnergy> in_;
  control::EnergyPacket received_;
  uint64_t invalid_packets_ = 0;
};

/// A node's trace columns tdpa_dissipated_j and tdpa_acting (1 while the controller acts, else 0)
/// from `link`, NaN without one, written at `row`; returns the position after them.
inline double* trace_tdpa_work(const TdpaLink* link, double* row) {
  const double none = std::numeric_limits<double>::quiet_NaN();
  *row++ = link != nullptr ? link->dissipated_energy_j() : none;
  *row++ = link != nullptr ? (link->acting() ? 1.0 : 0.0) : none;
  return row;
}

}  // namespace teleop::runtime
