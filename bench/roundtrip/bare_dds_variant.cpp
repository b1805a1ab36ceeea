// The bare Fast DDS variant (fastdds): the same samples, topics and pacing as the teleop
// variants, through BareDds on both sides; the pinger stamps the header itself.

#include <unistd.h>

#include <stdexcept>

#include "bare_dds.h"
#include "pinger.h"
#include "teleop/common/clock.h"

namespace teleop::bench {

VariantResult run_bare_dds_variant(const Options& opt) {
  VariantResult result;
  result.variant = Variant::kBareDds;
  const int64_t ready_deadline = monotonic_now_ns() + static_cast<int64_t>(opt.timeout_s * 1e9);
  EchoProcess echo(echo_args(Variant::kBareDds, opt));
  echo.wait_ready(ready_deadline);

  RttRecorder rec(opt.samples, opt.topics);  // outlives the endpoints, whose listeners feed it
  const std::string source = session_source();
  const TopicNames names = topic_names(opt.topics);
  BareDds dds(opt.domain, names.ping, names.pong, [&rec, &source](int topic, msg::JointState& reply) {
    const int64_t arrival = monotonic_now_ns();
    if (reply.header().source() != source) {
      rec.on_stray();
      return;
    }
    rec.on_reply(topic, reply.header().seq(), reply.header().stamp_mono_ns(), arrival);
  });
  std::vector<msg::JointState> samples(static_cast<size_t>(opt.topics), make_sample(source, opt.joints));
  while (!dds.all_matched()) {
    throw_if_stopped();
    echo.check_alive();
    if (monotonic_now_ns() > ready_deadline) throw std::runtime_error("the fastdds echo did not match in time");
    usleep(10'000);
  }

  run_paced(
      opt, rec, echo,
      [&dds, &samples](uint64_t seq) {
        bool ok = true;
        for (size_t i = 0; i < samples.size(); ++i) {
          samples[i].header().seq(seq);
          samples[i].header().stamp_mono_ns(monotonic_now_ns());
          ok = dds.write(static_cast<int>(i), samples[i]) && ok;
        }
        return ok;
      },
      result);
  return result;
}

}  // namespace teleop::bench
