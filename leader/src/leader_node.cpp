#include "leader_node.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "architectures/leader_architectures.h"
#include "teleop/common/clock.h"
#include "teleop/transport/arm_topic.h"
#include "teleop/transport/joint_fields.h"

namespace teleop::leader {
namespace {

// while leader.button_input is lost, the emergency stop reads pressed when one of its keys is it
uint32_t lost_stop_word(const LeaderConfig& config) {
  const int stop = config.stop_buttons.emergency_stop;
  for (const auto& key : config.button_input->keys) {
    if (key.second == stop) return 1u << stop;
  }
  return 0;
}

}  // namespace

LeaderNode::LeaderNode(const LeaderConfig& config, runtime::NodeContext& context)
    : config_(config),
      period_s_(1.0 / context.node.rate_hz),
      device_state_(context.participant, transport::arm_topic(transport::topics::kLeaderState, config.arm),
                    context.node.name),
      stop_requests_(context.participant, transport::topics::kEmergencyStop, context.node.name),
      follower_state_(context.participant, transport::arm_topic(transport::topics::kFollowerState, config.arm)),
      follower_wrench_(context.participant, transport::arm_topic(transport::topics::kFollowerWrench, config.arm)),
      twin_feedback_(context.participant, transport::arm_topic(transport::topics::kTwinFeedback, config.arm)),
      motion_(config.motion),
      clutch_(config.joints, config.workspace_scale),
      cartesian_(config.workspace_scale),
      renderer_(config.joints, config.feedback, context.node.rate_hz),
      hands_off_(config.hands_off) {
  const size_t n = config.joints;
  device_impl_ = config.device->make({period_s_, n, config.home_rad, config.arm_model, config.ee_site});
  // a Cartesian device has no joints: its pose is mapped as it is (architectures that need
  // joints refuse it with the configuration)
  if (!config.device->cartesian() && device_impl_->joints() != n) {
    throw std::runtime_error(std::string("leader: the ") + device_impl_->name() + " device has another joint count than leader.joints");
  }
  if (config.button_input) button_input_ = std::make_unique<ButtonInput>(*config.button_input, lost_stop_word(config));
  if (!config.arm_model.empty()) {
    if (!config.device->cartesian()) device_kinematics_ = std::make_unique<ArmKinematics>(config.arm_model, config.ee_site);
    command_kinematics_ = std::make_unique<ArmKinematics>(config.arm_model, config.ee_site);
  }
  architecture_ = make_leader_architecture(
      *config_.teleoperation.architecture,
      {config_, context, period_s_, {follower_state_, follower_wrench_, twin_feedback_}, device_state_});
  if (config.hand) hand_command_.emplace(context.participant, transport::topics::kHandCommand, context.node.name);
  watch_authority(context.participant, context.node.name);
  auto& st = device_state_.sample();
  st.robot("leader_device");
  st.arm(transport::arm_label(config.arm));
  transport::presize_joint_state(st, n);

  // the device starts wherever it is; the follower's command starts at home
  device_.q_rad = config.home_rad;
  device_connected_ = move_device(0.0);
  clutch_.start(device_.q_rad, config.home_rad);
  if (command_kinematics_) start_cartesian();
}

void LeaderNode::start_cartesian() {
  command_kinematics_->update(config_.home_rad, dq_cmd_);
  const Eigen::Vector3d& home = command_kinematics_->position();
  if (const auto& box = config_.workspace_box) {
    const Eigen::Vector3d min(box->min_m[0], box->min_m[1], box->min_m[2]);
    const Eigen::Vector3d max(box->max_m[0], box->max_m[1], box->max_m[2]);
    if ((home.array() < min.array()).any() || (home.array() > max.array()).any()) {
      throw std::runtime_error("leader.workspace_box_m: the follower's home flange position (" + std::to_string(home.x()) +
                               ", " + std::to_string(home.y()) + ", " + std::to_string(home.z()) + ") m is outside it");
    }
    cartesian_.bound(min, max);
  }
  if (device_kinematics_) device_kinematics_->update(device_.q_rad, device_.dq_radps);
  Eigen::Vector3d x;
  Eigen::Matrix3d r;
  control::Vector6 v;
  device_pose(x, r, v);
  cartesian_.start(x, r, home, command_kinematics_->rotation());
}

void LeaderNode::device_pose(Eigen::Vector3d& x, Eigen::Matrix3d& r, control::Vector6& v) const {
  if (device_kinematics_) {
    x = device_kinematics_->position();
    r = device_kinematics_->rotation();
    v = device_kinematics_->twist();
    return;
  }
  // a Cartesian device reports its pose itself
  const auto& p = device_.position_m;
  const auto& q = device_.orientation_wxyz;
  x = Eigen::Vector3d(p[0], p[1], p[2]);
  r = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
  for (int i = 0; i < 6; ++i) v[i] = device_.twist[static_cast<size_t>(i)];
}

void LeaderNode::watch_authority(transport::Participant& participant, const std::string& self) {
  authority_.emplace(participant, architecture_->authority_writer(), self, architecture_->authority_topic());
}

void LeaderNode::poll_peers() {
  follower_state_.poll();
  follower_wrench_.poll();
  twin_feedback_.poll();
  architecture_->receive();
}

void LeaderNode::update_state(int64_t now_ns) {
  const auto timeout = static_cast<int64_t>(config_.peer_timeout_s * 1e9);
  // the follower, and whatever else the architecture needs (model-mediated: the twin), must be there
  const bool fresh = follower_state_.age_ns(now_ns) < timeout && architecture_->peers_fresh(now_ns, timeout);
  authority_->poll(now_ns);
  // running means in command: the node that takes our commands follows us and has them in force
  const runtime::CommandRefusal refusal = authority_->refusal();
  const bool refused = refusal != runtime::CommandRefusal::kNone && refusal != runtime::CommandRefusal::kNoTaker &&
                       refusal != runtime::CommandRefusal::kNotYet;
  if (fresh && !authority_->in_command()) ++cycles_not_in_command_;
  // a device that cannot be read (unplugged) holds the command until it is back
  if (!device_connected_) {
    if (state_ == msg::STATE_RUNNING) {
      ++device_lost_events_;
      state_ = msg::STATE_SAFE_HOLD;
    }
    return;
  }
  if (fresh && authority_->in_command()) {
    if (state_ == msg::STATE_SAFE_HOLD) architecture_->restart();  // a new session with the follower
    state_ = msg::STATE_RUNNING;
  } else if (state_ == msg::STATE_RUNNING || (state_ == msg::STATE_STARTING && fresh && refused)) {
    // the peer went silent, or our commands are not in force: freeze the command where it is
    ++(fresh ? not_in_command_events_ : peer_lost_events_);
    state_ = msg::STATE_SAFE_HOLD;
  }
}

bool LeaderNode::move_device(double t_s) {
  // the simulated operator's intent moves a simulated device; a real one is held by a person
  motion_.sample(t_s, intent_.q_rad, intent_.dq_radps);
  motion_.intended_torque(t_s, intent_.tau_nm);
  intent_.hand_on = motion_.holding(t_s);
  device_impl_->set_operator_intent(intent_);
  // the buttons held in this cycle, whatever a device that has none leaves in the word
  device_.buttons = 0;
  const bool read = device_impl_->read(device_);
  if (!read) ++device_faults_;
  // the simulated operator's presses (leader.button_presses) and the input device's buttons on
  // top of what the device reports
  device_.buttons |= motion_.pressed_buttons(t_s);
  if (button_input_) device_.buttons |= button_input_->word();
  return read;
}

bool LeaderNode::dead_man_released() const {
  const int b = config_.stop_buttons.dead_man;
  return b >= 0 && (device_.buttons >> b & 1u) == 0;
}

bool LeaderNode::clutch_held() const {
  const int b = config_.stop_buttons.clutch;
  return b >= 0 && (device_.buttons >> b & 1u) != 0;
}

void LeaderNode::send_stop_requests(int64_t now_ns) {
  const auto pressed = [&](int button) { return button >= 0 && (device_.buttons >> button & 1u) != 0; };
  const auto was_pressed = [&](int button) { return button >= 0 && (buttons_before_ >> button & 1u) != 0; };
  const StopButtons& b = config_.stop_buttons;
  constexpr int64_t kRepeatNs = 100'000'000;
  auto send = [&](bool engaged, int button) {
    msg::EmergencyStop& s = stop_requests_.sample();
    s.engaged(engaged);
    s.target("");
    char origin[64];
    std::snprintf(origin, sizeof origin, "button %d of the leader's %s device", button, device_impl_->name());
    s.origin(origin);
    stop_requests_.publish();
  };
  if (pressed(b.emergency_stop) && (!was_pressed(b.emergency_stop) || now_ns - stop_sent_ns_ >= kRepeatNs)) {
    send(true, b.emergency_stop);
    stop_sent_ns_ = now_ns;
    ++stops_sent_;
  } else if (pressed(b.enable) && !was_pressed(b.enable) && !pressed(b.emergency_stop)) {
    send(false, b.enable);
    ++enables_sent_;
  }
  buttons_before_ = device_.buttons;
}

void LeaderNode::send_command(bool frozen) {
  // the joint mapping always runs: it is the device state the twin couples to
  q_cmd_ = clutch_.map(device_.q_rad, frozen);
  for (size_t i = 0; i < config_.joints; ++i) dq_cmd_[i] = frozen ? 0.0 : config_.workspace_scale * device_.dq_radps[i];
  if (device_kinematics_) device_kinematics_->update(device_.q_rad, device_.dq_radps);
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  control::Vector6 v = control::Vector6::Zero();
  if (device_kinematics_ || config_.device->cartesian()) device_pose(x, r, v);
  device_speed_mps_ = v.head<3>().norm();
  if (architecture_->cartesian()) {
    cartesian_.map(x, r, v, frozen);
    command_position_ = cartesian_.position();
  } else if (command_kinematics_) {
    // the commanded joints' flange position: only needed where the command is not Cartesian
    command_kinematics_->update(q_cmd_, dq_cmd_);
    command_position_ = command_kinematics_->position();
  }
  architecture_->send(mapped_device());
}

void LeaderNode::publish_device_state() {
  // the device's state in the follower's space (mapped by the clutch): what the twin couples to
  auto& st = device_state_.sample();
  transport::copy_joints(q_cmd_, config_.joints, st.q_rad());
  transport::copy_joints(dq_cmd_, config_.joints, st.dq_radps());
  transport::copy_joints(renderer_.output(), config_.joints, st.tau_measured_nm());
  device_state_.publish();
}

void LeaderNode::update_trace_values() {
  // what the operator feels, as a force in the follower's frame (undoing the workspace scaling); a
  // Cartesian device is rendered the force itself
  if (device_kinematics_) {
    felt_force_ = device_kinematics_->wrench_for_torque(renderer_.output()).head<3>() / config_.workspace_scale;
  } else if (config_.device->cartesian()) {
    felt_force_ = Eigen::Vector3d(renderer_.output()[0], renderer_.output()[1], renderer_.output()[2]) / config_.workspace_scale;
  }
}

void LeaderNode::cycle(const CycleTick& tick) {
  poll_peers();
  update_state(tick.now_ns);
  // the operator keeps moving; what the follower is sent freezes while it is lost
  operator_s_ = operator_time_s(tick);
  device_connected_ = move_device(operator_s_);
  send_stop_requests(tick.now_ns);
  command_hand(operator_s_);
  // the dead-man released or the clutch held, or the device let go (faster than a hand moves it,
  // hands_off_guard.h): the command holds, the device moves freely; a device that could not be
  // read moves nothing (update_state holds the leader from the next cycle)
  const bool released = dead_man_released();
  if (released || clutch_held()) ++cycles_held_by_buttons_;
  const bool let_go = hands_off_.update(device_speed_mps_, tick.now_ns) || released;
  const bool held = let_go || clutch_held();
  send_command(state_ == msg::STATE_SAFE_HOLD || emergency_stopped_ || held || !device_connected_);
  const bool fresh = architecture_->feedback(mapped_device(), tick.now_ns, feedback_, rejected_feedback_);
  // lost or stale source, the follower gone, an emergency stop, the clutch, or the operator's
  // hand off the device (quicker then): fade the feedback out, never cut it
  renderer_.render(feedback_, config_.feedback_enabled && fresh && state_ == msg::STATE_RUNNING && !emergency_stopped_ &&
                                  !held,
                   let_go);
  device_refused_ = !device_impl_->write(renderer_.output());
  if (device_refused_) ++device_faults_;
  publish_device_state();
  update_trace_values();
}

// the operator's hand: the plan's targets to the hand node (which holds them, and reports a
// stale command, if the leader goes away)
void LeaderNode::command_hand(double t_s) {
  if (!hand_command_) return;
  msg::HandCommand& c = hand_command_->sample();
  config_.hand->sample(t_s, c.target_position_rad(), c.current_limit_a());
  c.enable(true);
  c.fault_reset(false);
  hand_command_->publish();
}

void LeaderNode::fill_status(msg::NodeStatus& status) const {
  architecture_->fill_status(status);
}

void LeaderNode::active_faults(std::vector<uint32_t>& faults) const {
  const int64_t now_ns = monotonic_now_ns();
  const bool fresh = follower_state_.age_ns(now_ns) < static_cast<int64_t>(config_.peer_timeout_s * 1e9);
  // held for its device (unplugged), or for the follower: not in command, or gone
  if (state_ == msg::STATE_SAFE_HOLD && device_connected_) {
    faults.push_back(fresh ? msg::FAULT_NOT_IN_COMMAND : msg::FAULT_PEER_LOST);
  }
  // the device as it is now: one that came back (a master arm's first state late, a replug) is no fault
  if (!device_connected_ || device_refused_) faults.push_back(msg::FAULT_HARDWARE);
}

void LeaderNode::fill_report(runtime::NodeReport& report) const {
  architecture_->report_command(report);
  if (hand_command_) report.add(*hand_command_);
  report.add(device_state_);
  report.add(follower_state_);
  report.add(follower_wrench_);
  report.add(twin_feedback_);
  architecture_->report_channel(report);
  report.counters.emplace_back("peer_lost_events", static_cast<double>(peer_lost_events_));
  report.counters.emplace_back("not_in_command_events", static_cast<double>(not_in_command_events_));
  report.counters.emplace_back("cycles_not_in_command", static_cast<double>(cycles_not_in_command_));
  report.counters.emplace_back("in_command", authority_->in_command() ? 1.0 : 0.0);
  report.counters.emplace_back("device_faults", static_cast<double>(device_faults_));
  report.counters.emplace_back("device_lost_events", static_cast<double>(device_lost_events_));
  device_impl_->report_counters(report.counters);
  report.counters.emplace_back("cycles_held_by_buttons", static_cast<double>(cycles_held_by_buttons_));
  report.counters.emplace_back("hands_off_events", static_cast<double>(hands_off_.events()));
  report.counters.emplace_back("workspace_box_saturations", static_cast<double>(cartesian_.box_saturations()));
  report.counters.emplace_back("emergency_stops_sent", static_cast<double>(stops_sent_));
  if (button_input_) report.counters.emplace_back("button_input_losses", static_cast<double>(button_input_->losses()));
  report.counters.emplace_back("enables_sent", static_cast<double>(enables_sent_));
  report.counters.emplace_back("rejected_feedback", static_cast<double>(rejected_feedback_));
  report.counters.emplace_back("feedback_peak_nm", renderer_.peak_nm());
  report.counters.emplace_back("feedback_saturations", static_cast<double>(renderer_.saturations()));
  report.counters.emplace_back("feedback_rate_limited", static_cast<double>(renderer_.rate_limited()));
}

void LeaderNode::trace_columns(std::vector<std::string>& columns) const {
  for (const char* c : {"x_cmd_x", "x_cmd_y", "x_cmd_z", "f_felt_x", "f_felt_y", "f_felt_z", "tdpa_w_j", "feedback_fade", "state",
                        "peer_session", "operator_s", "tdpa_dissipated_j", "tdpa_acting"}) {
    columns.emplace_back(c);
  }
  for (size_t i = 0; i < config_.joints; ++i) columns.push_back("q_dev_" + std::to_string(i));
  for (size_t i = 0; i < config_.joints; ++i) columns.push_back("dq_dev_" + std::to_string(i));
  for (size_t i = 0; i < config_.joints; ++i) columns.push_back("tau_fb_" + std::to_string(i));
}

double LeaderNode::operator_time_s(const CycleTick& tick) {
  if (!config_.motion.starts_in_command) return static_cast<double>(tick.index) * period_s_;
  if (!operator_started_ && state_ == msg::STATE_RUNNING) {
    operator_started_ = true;
    operator_start_index_ = tick.index;
  }
  return operator_started_ ? static_cast<double>(tick.index - operator_start_index_) * period_s_ : 0.0;
}

void LeaderNode::trace_row(double* row) const {
  const double nan = std::nan("");
  const bool kinematics = device_kinematics_ != nullptr || config_.device->cartesian();
  for (int i = 0; i < 3; ++i) *row++ = command_position_[i];
  for (int i = 0; i < 3; ++i) *row++ = kinematics ? felt_force_[i] : nan;
  *row++ = architecture_->observed_energy_j();
  *row++ = renderer_.fade();
  *row++ = static_cast<double>(state_);
  // which follower's state the leader follows (a restarted follower opens a new session)
  *row++ = static_cast<double>(follower_state_.session().session());
  // the simulated operator's clock (leader.motion_starts): 0 until its motion starts
  *row++ = operator_s_;
  row = runtime::trace_tdpa_work(architecture_->tdpa(), row);
  row = std::copy_n(device_.q_rad.begin(), config_.joints, row);
  row = std::copy_n(device_.dq_radps.begin(), config_.joints, row);
  std::copy_n(renderer_.output().begin(), config_.joints, row);
}

}  // namespace teleop::leader
