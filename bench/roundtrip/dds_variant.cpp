// The teleop variants (dds-udp, dds-shm, dds-sec): the sample goes out on leader/joint_state
// through a Publication and comes back on follower/joint_state from the echo.

#include <unistd.h>

#include <stdexcept>

#include "pinger.h"
#include "teleop/common/clock.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/publication.h"
#include "teleop/transport/topics.h"

namespace teleop::bench {
namespace {

using msg::JointState;

/// Waits until the echo's reader and writer matched ours; throws after `deadline_mono_ns`.
void wait_for_match(Variant v, const Options& opt, const transport::Publication<JointState>& pub,
                    const transport::Reader<JointState>& reader, EchoProcess& echo, int64_t deadline_mono_ns) {
  while (pub.matched() < 1 || reader.matched() < 1) {
    throw_if_stopped();
    echo.check_alive();
    if (monotonic_now_ns() > deadline_mono_ns) {
      throw std::runtime_error(std::string("the ") + name_of(v) + " echo did not match within " +
                               seconds_text(opt.timeout_s) + " s (writer matched " + std::to_string(pub.matched()) +
                               ", reader matched " + std::to_string(reader.matched()) +
                               "); is DDS discovery blocked on domain " + std::to_string(opt.domain) + "?");
    }
    usleep(10'000);
  }
}

}  // namespace

VariantResult run_dds_variant(Variant v, const Options& opt) {
  VariantResult result;
  result.variant = v;
  const int64_t ready_deadline = monotonic_now_ns() + static_cast<int64_t>(opt.timeout_s * 1e9);
  EchoProcess echo(echo_args(v, opt));  // before any DDS entity of this variant exists
  echo.wait_ready(ready_deadline);

  RttRecorder rec(opt.samples);  // outlives the participant, whose callback feeds it
  const std::string source = session_source();
  transport::Participant participant(dds_config(v, opt.domain, "teleop_bench_ping", opt.pki, "leader"));
  transport::Publication<JointState> pub(participant, transport::topics::kLeaderState, source);
  pub.sample() = make_sample(source);
  auto reader =
      participant.make_reader<JointState>(transport::topics::kFollowerState, [&rec, &source](const JointState& reply) {
        const int64_t arrival = monotonic_now_ns();
        // only our own samples: another bench or demo on the same domain must not be counted
        if (reply.header().source() != source) {
          rec.on_stray();
          return;
        }
        rec.on_reply(reply.header().seq(), reply.header().stamp_mono_ns(), arrival);
      });
  wait_for_match(v, opt, pub, reader, echo, ready_deadline);

  run_paced(
      opt, rec, echo,
      [&pub](uint64_t /*seq*/) {
        return pub.publish();  // stamps the next seq (== the loop's count) and the monotonic time
      },
      result);
  return result;
}

}  // namespace teleop::bench
