#include "teleop/runtime/tdpa_link.h"

#include <algorithm>

#include "teleop/transport/arm_topic.h"
#include "teleop/transport/joint_fields.h"

namespace teleop::runtime {
namespace {

control::PassivityPortConfig port_config(TdpaEnd end, std::size_t channels, double cycle_s, bool enabled,
                                         double max_damping) {
  control::PassivityPortConfig c;
  c.channels = channels;
  c.cycle_s = cycle_s;
  // the leader's end delivers a force to the operator, the follower's a velocity to the robot
  c.causality = end == TdpaEnd::kLeader ? control::PortCausality::kForceOutput : control::PortCausality::kVelocityOutput;
  c.controller_enabled = enabled;
  c.max_damping = max_damping;
  return c;
}

}  // namespace

TdpaLink::TdpaLink(transport::Participant& participant, const std::string& node_name, const std::string& arm,
                   TdpaEnd end, std::size_t channels, double cycle_s, bool controller_enabled, double max_damping)
    : port_(port_config(end, channels, cycle_s, controller_enabled, max_damping)),
      out_(participant, transport::arm_topic(end == TdpaEnd::kLeader ? transport::topics::kTdpaLeaderToFollower
                                                                     : transport::topics::kTdpaFollowerToLeader,
                                             arm),
           node_name),
      in_(participant, transport::arm_topic(end == TdpaEnd::kLeader ? transport::topics::kTdpaFollowerToLeader
                                                                    : transport::topics::kTdpaLeaderToFollower,
                                            arm)) {
  transport::presize(channels, out_.sample().energy_in_j(), out_.sample().energy_out_j());
  received_.channels = channels;
}

void TdpaLink::receive() {
  if (in_.poll() == 0) return;
  const msg::TdpaEnergy& m = in_.latest();
  // a packet of another channel count is invalid: RemoteEnergy rejects it by its count
  received_.seq = m.header().seq();
  received_.session = m.session();
  received_.channels = m.energy_in_j().size();
  const std::size_t n = std::min(received_.channels, control::kMaxTdpaChannels);
  std::copy_n(m.energy_in_j().begin(), n, received_.energy_in_j.begin());
  std::copy_n(m.energy_out_j().begin(), std::min(n, m.energy_out_j().size()), received_.energy_out_j.begin());
  if (port_.receive(received_) == control::PacketVerdict::kInvalid) ++invalid_packets_;
}

control::PortStatus TdpaLink::update(std::span<const double> force, std::span<const double> velocity,
                                     std::span<double> corrected) {
  return port_.update(force, velocity, corrected);
}

void TdpaLink::publish() {
  const control::EnergyPacket& p = port_.make_packet();
  auto& m = out_.sample();
  std::copy_n(p.energy_in_j.begin(), p.channels, m.energy_in_j().begin());
  std::copy_n(p.energy_out_j.begin(), p.channels, m.energy_out_j().begin());
  m.session(p.session);
  // the header's sequence number is the packet's: Publication numbers every sample it sends
  out_.publish();
}

double TdpaLink::observed_energy_j() const {
  double w = port_.observed_energy_j(0);
  for (std::size_t i = 1; i < port_.config().channels; ++i) w = std::min(w, port_.observed_energy_j(i));
  return w;
}

double TdpaLink::dissipated_energy_j() const {
  double dissipated = 0.0;
  for (std::size_t i = 0; i < port_.config().channels; ++i) dissipated += port_.dissipated_energy_j(i);
  return dissipated;
}

bool TdpaLink::acting() const {
  for (std::size_t i = 0; i < port_.config().channels; ++i) {
    if (port_.damping(i) > 0.0) return true;
  }
  return false;
}

void TdpaLink::fill_report(runtime::NodeReport& report) const {
  report.add(out_);
  report.add(in_);
  const auto& c = port_.counters();
  report.counters.emplace_back("tdpa_min_observed_energy_j", port_.min_observed_energy_j());
  report.counters.emplace_back("tdpa_dissipated_j", dissipated_energy_j());
  report.counters.emplace_back("tdpa_deficit_cycles", static_cast<double>(c.deficits));
  report.counters.emplace_back("tdpa_damper_saturations", static_cast<double>(c.saturations));
  report.counters.emplace_back("tdpa_non_finite_inputs", static_cast<double>(c.non_finite_inputs));
  report.counters.emplace_back("tdpa_packets_missed", static_cast<double>(port_.remote().counters().missed));
  report.counters.emplace_back("tdpa_packets_invalid", static_cast<double>(invalid_packets_));
  report.counters.emplace_back("tdpa_session", static_cast<double>(port_.session()));
  report.counters.emplace_back("tdpa_remote_restarts", static_cast<double>(c.remote_restarts));
}

}  // namespace teleop::runtime
