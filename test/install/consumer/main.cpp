// A program outside teleop's tree: it joins a follower's bus with teleop::transport, reads the
// follower's joint state and streams joint commands that hold the arm where it is.
//   teleop_consumer DOMAIN SECONDS
// Prints how many commands it sent and states it received; exit status 0 when both flowed.
#include <teleop/msg/arm.h>
#include <teleop/transport/participant.h>
#include <teleop/transport/publication.h>
#include <teleop/transport/subscription.h>
#include <teleop/transport/topics.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: teleop_consumer DOMAIN SECONDS\n");
    return 2;
  }
  using namespace teleop;
  using namespace std::chrono;
  transport::ParticipantConfig config;
  config.domain_id = std::stoi(argv[1]);
  config.name = "consumer";
  const auto run_for = duration<double>(std::stod(argv[2]));

  transport::Participant participant(config);
  transport::Subscription<msg::JointState> state(participant, transport::topics::kFollowerState);
  transport::Publication<msg::JointCommand> command(participant, transport::topics::kLeaderCommand, "consumer");

  // wait for the follower's state: its pose is the one to hold
  const auto give_up = steady_clock::now() + seconds(15);
  while (state.poll() == 0 || !state.has_sample()) {
    if (steady_clock::now() > give_up) {
      std::fprintf(stderr, "consumer: no joint state from the follower within 15 s\n");
      return 1;
    }
    std::this_thread::sleep_for(milliseconds(1));
  }
  const msg::JointState& held = state.latest();
  const size_t joints = held.q_rad().size();
  msg::JointCommand& c = command.sample();
  c.robot(held.robot());
  c.arm(held.arm());
  c.mode().assign(joints, msg::CONTROL_JOINT_IMPEDANCE);
  c.q_des_rad(held.q_rad());
  c.dq_des_radps().assign(joints, 0.0);
  c.tau_ff_nm().assign(joints, 0.0);
  c.stiffness_nm_per_rad().assign(joints, 100.0);
  c.damping_nms_per_rad().assign(joints, 10.0);

  // 1 kHz, as a leader streams
  uint64_t states = 1;
  const auto end = steady_clock::now() + duration_cast<steady_clock::duration>(run_for);
  auto next = steady_clock::now();
  while (next < end) {
    command.publish();
    states += static_cast<uint64_t>(state.poll());
    next += milliseconds(1);
    std::this_thread::sleep_until(next);
  }
  // what is still in flight reaches the follower before we leave the bus
  command.wait_for_acknowledgments(1'000'000'000);
  std::printf("consumer: sent %llu commands (%llu refused), received %llu states of %zu joints\n",
              static_cast<unsigned long long>(command.sent()), static_cast<unsigned long long>(command.failed()),
              static_cast<unsigned long long>(states), joints);
  return command.sent() > 0 && command.failed() == 0 && states > 1 ? 0 : 1;
}
