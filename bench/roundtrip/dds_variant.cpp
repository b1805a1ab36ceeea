// The teleop variants (dds-udp, dds-imp, dds-shm, dds-sec): each sample goes out through a
// Publication on leader/joint_state (and its numbered siblings with --topics) and comes back on
// follower/joint_state from the echo.

#include <unistd.h>

#include <memory>
#include <stdexcept>

#include "pinger.h"
#include "teleop/common/clock.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/publication.h"

namespace teleop::bench {
namespace {

using msg::JointState;
using Publication = transport::Publication<JointState>;
using Reader = transport::Reader<JointState>;

/// Waits until the echo's readers and writers matched ours; throws after `deadline_mono_ns`.
void wait_for_match(Variant v, const Options& opt, const std::vector<std::unique_ptr<Publication>>& pubs,
                    const std::vector<Reader>& readers, EchoProcess& echo, int64_t deadline_mono_ns) {
  const auto all_matched = [&] {
    for (const auto& p : pubs) {
      if (p->matched() < 1) return false;
    }
    for (const auto& r : readers) {
      if (r.matched() < 1) return false;
    }
    return true;
  };
  while (!all_matched()) {
    throw_if_stopped();
    echo.check_alive();
    if (monotonic_now_ns() > deadline_mono_ns) {
      throw std::runtime_error(std::string("the ") + name_of(v) + " echo did not match within " +
                               seconds_text(opt.timeout_s) + " s (writer matched " +
                               std::to_string(pubs.front()->matched()) + ", reader matched " +
                               std::to_string(readers.front().matched()) + "); is DDS discovery blocked on domain " +
                               std::to_string(opt.domain) + "?");
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

  RttRecorder rec(opt.samples, opt.topics);  // outlives the participant, whose callbacks feed it
  const std::string source = session_source();
  const TopicNames names = topic_names(opt.topics);
  transport::Participant participant(dds_config(v, opt.domain, "teleop_bench_ping", opt.pki, "leader"));
  std::vector<std::unique_ptr<Publication>> pubs;
  std::vector<Reader> readers;
  for (int i = 0; i < opt.topics; ++i) {
    const auto idx = static_cast<size_t>(i);
    pubs.push_back(std::make_unique<Publication>(
        participant, transport::TopicSpec<JointState>{names.ping[idx].c_str(), transport::QosPreset::kStream}, source));
    pubs.back()->sample() = make_sample(source, opt.joints);
    readers.push_back(participant.make_reader<JointState>(
        transport::TopicSpec<JointState>{names.pong[idx].c_str(), transport::QosPreset::kStream},
        [&rec, &source, i](const JointState& reply) {
          const int64_t arrival = monotonic_now_ns();
          // only our own samples: another bench or demo on the same domain must not be counted
          if (reply.header().source() != source) {
            rec.on_stray();
            return;
          }
          rec.on_reply(i, reply.header().seq(), reply.header().stamp_mono_ns(), arrival);
        }));
  }
  wait_for_match(v, opt, pubs, readers, echo, ready_deadline);

  run_paced(
      opt, rec, echo,
      [&pubs](uint64_t /*seq*/) {
        bool ok = true;
        // stamps the next seq (== the loop's count) and the monotonic time
        for (auto& p : pubs) ok = p->publish() && ok;
        return ok;
      },
      result);
  return result;
}

}  // namespace teleop::bench
