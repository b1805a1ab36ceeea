#include "teleop/transport/participant.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "teleop/common/clock.h"
#include "teleop/transport/joint_fields.h"
#include "teleop/transport/publication.h"
#include "teleop/transport/subscription.h"

extern char** environ;

namespace teleop::transport {
namespace {

constexpr size_t kJoints = 7;

// The helper process of CountsLivelinessLostWhenWriterProcessIsKilled learns the test's domain
// and topic owner through these.
constexpr const char* kHelperDomainEnv = "TELEOP_PARTICIPANT_TEST_HELPER_DOMAIN";
constexpr const char* kHelperOwnerEnv = "TELEOP_PARTICIPANT_TEST_HELPER_OWNER";

// The test process's pid (the helper's parent's, in the helper).
const std::string& topic_owner() {
  static const std::string owner = [] {
    const char* env = std::getenv(kHelperOwnerEnv);
    return env != nullptr ? std::string(env) : std::to_string(getpid());
  }();
  return owner;
}

// Topics of this test process only: their names carry its pid, so that concurrent test runs
// never match each other's endpoints, even when their domains (below) happen to coincide.
TopicSpec<msg::JointState> topic(const std::string& leaf, QosPreset preset) {
  static std::map<std::string, std::string> names;  // stable storage for the names
  std::string& name = names[leaf];
  if (name.empty()) name = "teleop_test/" + topic_owner() + "/" + leaf;
  return {name.c_str(), preset};
}
TopicSpec<msg::JointState> stream_topic() { return topic("stream", QosPreset::kStream); }
TopicSpec<msg::JointState> state_topic() { return topic("state", QosPreset::kState); }

// A domain per test process, so that concurrent test runs rarely even share discovery traffic.
int test_domain() { return static_cast<int>(getpid() % 100) + 100; }

// UDP and shared memory. Participants of this process find each other through the default
// multicast discovery, which the shared-memory transport carries even where UDP multicast is
// unavailable. The library turns intra-process delivery off, so samples do cross a transport.
ParticipantConfig config(const std::string& name, int domain = test_domain()) {
  ParticipantConfig c;
  c.domain_id = domain;
  c.name = name;
  c.udpv4 = true;
  c.shm = true;
  return c;
}

// Across processes where one gets killed: UDP only (a killed process would leave its
// shared-memory segments behind), discovered by unicast on the loopback, which works without
// multicast. Initial peers reach the first participant ids of a host, and the helper process's
// participant is the first of its process.
ParticipantConfig udp_config(const std::string& name, int domain = test_domain()) {
  ParticipantConfig c = config(name, domain);
  c.shm = false;
  c.initial_peers = {"127.0.0.1"};
  return c;
}

// Polls `done` every millisecond until it holds or `timeout` passes; returns its last value.
// The timeout is generous on purpose: it bounds a hang, it does not measure anything.
bool wait_for(const std::function<bool()>& done, std::chrono::milliseconds timeout = std::chrono::seconds(5)) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (!done()) {
    if (std::chrono::steady_clock::now() > end) return done();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

void fill(msg::JointState& s, int i) {
  s.robot("panda");
  s.arm(i % 2 ? "left" : "right");
  presize_joint_state(s, kJoints);
  for (size_t j = 0; j < kJoints; ++j) {
    s.q_rad()[j] = i + 0.01 * static_cast<double>(j);
    s.dq_radps()[j] = -i - 0.5 * static_cast<double>(j);
    s.tau_measured_nm()[j] = 1000.0 * i + static_cast<double>(j);
    s.tau_ext_nm()[j] = 0.25 * i;
  }
}

void expect_payload(const msg::JointState& s, int i) {
  EXPECT_EQ(s.robot().to_string(), "panda");
  EXPECT_EQ(s.arm().to_string(), i % 2 ? "left" : "right");
  ASSERT_EQ(s.q_rad().size(), kJoints);
  ASSERT_EQ(s.dq_radps().size(), kJoints);
  ASSERT_EQ(s.tau_measured_nm().size(), kJoints);
  ASSERT_EQ(s.tau_ext_nm().size(), kJoints);
  for (size_t j = 0; j < kJoints; ++j) {
    EXPECT_EQ(s.q_rad()[j], i + 0.01 * static_cast<double>(j)) << "sample " << i << " joint " << j;
    EXPECT_EQ(s.dq_radps()[j], -i - 0.5 * static_cast<double>(j)) << "sample " << i << " joint " << j;
    EXPECT_EQ(s.tau_measured_nm()[j], 1000.0 * i + static_cast<double>(j)) << "sample " << i << " joint " << j;
    EXPECT_EQ(s.tau_ext_nm()[j], 0.25 * i) << "sample " << i << " joint " << j;
  }
}

TEST(Participant, ExposesItsConfigurationWhenCreated) {
  Participant p(config("cfg_check"));
  EXPECT_EQ(p.config().name, "cfg_check");
  EXPECT_EQ(p.config().domain_id, test_domain());
  ASSERT_NE(p.dds(), nullptr);
  EXPECT_EQ(p.dds()->get_domain_id(), static_cast<uint32_t>(test_domain()));
}

TEST(Participant, DeliversEverySampleWithHeaderAndPayloadWhenPolled) {
  Participant writer_side(config("writer_side"));
  Participant reader_side(config("reader_side"));
  Publication<msg::JointState> pub(writer_side, stream_topic(), "leader_a");
  Subscription<msg::JointState> sub(reader_side, stream_topic());
  EXPECT_EQ(pub.topic_name(), std::string(stream_topic().name));
  EXPECT_EQ(sub.topic_name(), std::string(stream_topic().name));
  EXPECT_FALSE(sub.has_sample());
  EXPECT_EQ(sub.age_ns(monotonic_now_ns()), INT64_MAX);

  ASSERT_TRUE(wait_for([&] { return pub.matched() == 1 && sub.reader().matched() == 1; }))
      << "writer matched " << pub.matched() << ", reader matched " << sub.reader().matched();

  constexpr int kSamples = 50;
  std::vector<msg::JointState> received;
  for (int i = 1; i <= kSamples; ++i) {
    fill(pub.sample(), i);
    ASSERT_TRUE(pub.publish()) << "sample " << i;
    // one sample in flight at a time: the reader's keep-last history can never overwrite one
    ASSERT_TRUE(wait_for([&] {
      sub.poll();
      return sub.has_sample() && sub.latest().header().seq() == static_cast<uint64_t>(i);
    })) << "sample " << i << " did not arrive";
    received.push_back(sub.latest());
  }

  EXPECT_EQ(pub.sent(), static_cast<uint64_t>(kSamples));
  EXPECT_EQ(pub.failed(), 0u);
  ASSERT_EQ(received.size(), static_cast<size_t>(kSamples));
  for (int i = 1; i <= kSamples; ++i) {
    const msg::JointState& s = received[static_cast<size_t>(i - 1)];
    EXPECT_EQ(s.header().seq(), static_cast<uint64_t>(i));
    EXPECT_EQ(s.header().source().to_string(), "leader_a");
    EXPECT_GT(s.header().stamp_ns(), 0);
    EXPECT_GT(s.header().stamp_mono_ns(), 0);
    expect_payload(s, i);
  }
  // stamps are taken at publish time, in order
  for (size_t k = 1; k < received.size(); ++k) {
    EXPECT_GE(received[k].header().stamp_mono_ns(), received[k - 1].header().stamp_mono_ns());
  }

  const SequenceTracker& stats = sub.stats();
  EXPECT_EQ(stats.received(), static_cast<uint64_t>(kSamples));
  EXPECT_EQ(stats.first_seq(), 1u);
  EXPECT_EQ(stats.last_seq(), static_cast<uint64_t>(kSamples));
  EXPECT_EQ(stats.expected(), static_cast<uint64_t>(kSamples));
  EXPECT_EQ(stats.lost(), 0u);  // one sample in flight on this host: no tolerance needed
  EXPECT_EQ(stats.duplicates(), 0u);
  EXPECT_EQ(stats.reordered(), 0u);
  EXPECT_EQ(stats.latency().count(), static_cast<uint64_t>(kSamples));
  EXPECT_TRUE(sub.has_sample());
  EXPECT_EQ(sub.latest().header().seq(), static_cast<uint64_t>(kSamples));
  EXPECT_LT(sub.age_ns(monotonic_now_ns()), INT64_MAX);
  EXPECT_GE(sub.age_ns(monotonic_now_ns()), 0);
}

TEST(Participant, KeepsNewestSampleAsLatestWhenSeveralArriveBetweenPolls) {
  Participant writer_side(config("burst_writer"));
  Participant reader_side(config("burst_reader"));
  Publication<msg::JointState> pub(writer_side, stream_topic(), "burst");
  Subscription<msg::JointState> sub(reader_side, stream_topic());
  ASSERT_TRUE(wait_for([&] { return pub.matched() == 1 && sub.reader().matched() == 1; }));

  // fewer than the stream reader's history depth, so all of them are kept until the poll
  constexpr int kBurst = kReaderDepth / 2;
  for (int i = 1; i <= kBurst; ++i) {
    fill(pub.sample(), i);
    ASSERT_TRUE(pub.publish());
  }
  int taken = 0;
  ASSERT_TRUE(wait_for([&] {
    taken += sub.poll();
    return taken >= kBurst;
  }));
  EXPECT_EQ(taken, kBurst);
  EXPECT_EQ(sub.latest().header().seq(), static_cast<uint64_t>(kBurst));
  expect_payload(sub.latest(), kBurst);
  EXPECT_EQ(sub.stats().received(), static_cast<uint64_t>(kBurst));
  EXPECT_EQ(sub.stats().lost(), 0u);
  EXPECT_EQ(sub.poll(), 0);  // drained
}

TEST(Participant, CallsCallbackForEverySampleWhenReaderIsInCallbackMode) {
  Participant writer_side(config("cb_writer"));
  Participant reader_side(config("cb_reader"));
  Publication<msg::JointState> pub(writer_side, stream_topic(), "cb_source");

  std::mutex mutex;
  std::vector<msg::JointState> got;
  Reader<msg::JointState> reader = reader_side.make_reader<msg::JointState>(stream_topic(), [&](const msg::JointState& s) {
    std::lock_guard<std::mutex> lock(mutex);
    got.push_back(s);
  });
  ASSERT_TRUE(reader.valid());
  ASSERT_TRUE(wait_for([&] { return pub.matched() == 1 && reader.matched() == 1; }));

  const auto count = [&] {
    std::lock_guard<std::mutex> lock(mutex);
    return got.size();
  };
  constexpr int kSamples = 20;
  for (int i = 1; i <= kSamples; ++i) {
    fill(pub.sample(), i);
    ASSERT_TRUE(pub.publish());
    ASSERT_TRUE(wait_for([&] { return count() >= static_cast<size_t>(i); })) << "sample " << i << " did not arrive";
  }

  std::lock_guard<std::mutex> lock(mutex);
  ASSERT_EQ(got.size(), static_cast<size_t>(kSamples));
  for (int i = 1; i <= kSamples; ++i) {
    const msg::JointState& s = got[static_cast<size_t>(i - 1)];
    EXPECT_EQ(s.header().seq(), static_cast<uint64_t>(i));
    EXPECT_EQ(s.header().source().to_string(), "cb_source");
    expect_payload(s, i);
  }
}

TEST(Participant, DeliversLastStateSampleWhenReaderJoinsLate) {
  Participant writer_side(config("state_writer"));
  Publication<msg::JointState> pub(writer_side, state_topic(), "state_source");
  for (int i = 1; i <= 3; ++i) {
    fill(pub.sample(), i);
    ASSERT_TRUE(pub.publish());
  }
  // the reader only exists after the last write: transient-local keep-last 1 hands it sample 3
  Participant reader_side(config("state_reader"));
  Subscription<msg::JointState> sub(reader_side, state_topic());
  ASSERT_TRUE(wait_for([&] {
    sub.poll();
    return sub.has_sample();
  })) << "the late joiner got nothing; matched " << sub.reader().matched();
  EXPECT_EQ(sub.latest().header().seq(), 3u);
  EXPECT_EQ(sub.latest().header().source().to_string(), "state_source");
  expect_payload(sub.latest(), 3);
  EXPECT_EQ(sub.stats().received(), 1u);
}

TEST(Participant, DoesNotMatchWhenPresetsDiffer) {
  // a best-effort writer cannot serve a reliable reader
  const TopicSpec<msg::JointState> stream_on_same_name = topic("mixed", QosPreset::kStream);
  const TopicSpec<msg::JointState> state_on_same_name = topic("mixed", QosPreset::kState);
  ASSERT_STREQ(stream_on_same_name.name, state_on_same_name.name);
  Participant writer_side(config("mixed_writer"));
  Participant reader_side(config("mixed_reader"));
  Publication<msg::JointState> pub(writer_side, stream_on_same_name, "mixed");
  Subscription<msg::JointState> sub(reader_side, state_on_same_name);
  // a positive control on the stream topic shows that discovery itself works
  Publication<msg::JointState> control_pub(writer_side, stream_topic(), "control");
  Subscription<msg::JointState> control_sub(reader_side, stream_topic());
  ASSERT_TRUE(wait_for([&] { return control_pub.matched() == 1 && control_sub.reader().matched() == 1; }));
  // discovery of both pairs travels in the same announcements; give the mixed pair a moment more
  EXPECT_FALSE(wait_for([&] { return pub.matched() > 0 || sub.reader().matched() > 0; }, std::chrono::milliseconds(500)));
}

TEST(Participant, ReaderSeesWriterGoneWhenWriterParticipantIsDestroyed) {
  Participant reader_side(config("lv_reader"));
  Subscription<msg::JointState> sub(reader_side, stream_topic());
  {
    Participant writer_side(config("lv_writer"));
    Publication<msg::JointState> pub(writer_side, stream_topic(), "lv_writer");
    ASSERT_TRUE(wait_for([&] { return pub.matched() == 1 && sub.reader().matched() == 1; }));
    fill(pub.sample(), 1);
    ASSERT_TRUE(pub.publish());
    ASSERT_TRUE(wait_for([&] { return sub.reader().alive_writers() == 1; }))
        << "alive writers " << sub.reader().alive_writers();
  }  // the writer's participant is deleted here
  EXPECT_TRUE(wait_for([&] { return sub.reader().alive_writers() == 0; }))
      << "alive writers " << sub.reader().alive_writers();
  EXPECT_TRUE(wait_for([&] { return sub.reader().matched() == 0; })) << "matched " << sub.reader().matched();
}

// ---- a writer in another process that dies without saying goodbye ----

// The body of the helper process: publishes every 10 ms until killed (or 60 s pass).
[[noreturn]] void run_writer_child(int domain) {
  // never outlive the test process, whatever happens to it
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (std::to_string(getppid()) != topic_owner()) std::_Exit(1);
  Participant participant(udp_config("killed_writer", domain));
  Publication<msg::JointState> pub(participant, stream_topic(), "killed_writer");
  fill(pub.sample(), 1);
  for (int i = 0; i < 6000; ++i) {
    (void)pub.publish();
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::_Exit(0);
}

// When this executable is started as the helper (see below), it runs the writer before main().
[[maybe_unused]] const bool g_writer_child = [] {
  if (const char* domain = std::getenv(kHelperDomainEnv)) run_writer_child(std::atoi(domain));
  return false;
}();

TEST(Participant, CountsLivelinessLostWhenWriterProcessIsKilled) {
  Participant reader_side(udp_config("lv_observer"));
  Subscription<msg::JointState> sub(reader_side, stream_topic());

  std::vector<std::string> env_strings;
  for (char** e = environ; *e != nullptr; ++e) env_strings.emplace_back(*e);
  env_strings.push_back(std::string(kHelperDomainEnv) + "=" + std::to_string(test_domain()));
  env_strings.push_back(std::string(kHelperOwnerEnv) + "=" + topic_owner());
  std::vector<char*> envp;
  for (auto& s : env_strings) envp.push_back(s.data());
  envp.push_back(nullptr);
  std::string self = "/proc/self/exe";
  char* argv[] = {self.data(), nullptr};
  pid_t child = 0;
  ASSERT_EQ(posix_spawn(&child, "/proc/self/exe", nullptr, nullptr, argv, envp.data()), 0);

  // alive, and delivering
  const bool alive = wait_for(
      [&] {
        sub.poll();
        return sub.reader().alive_writers() == 1 && sub.stats().received() > 0;
      },
      std::chrono::seconds(10));
  const uint64_t lost_before = sub.reader().liveliness_lost();
  kill(child, SIGKILL);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(alive) << "the writer process never became alive and delivering; matched " << sub.reader().matched()
                     << ", alive " << sub.reader().alive_writers() << ", received " << sub.stats().received();
  EXPECT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(lost_before, 0u);

  // the lease (250 ms by default) expires with nobody asserting it
  EXPECT_TRUE(wait_for([&] { return sub.reader().liveliness_lost() >= 1; }))
      << "liveliness lost " << sub.reader().liveliness_lost();
  EXPECT_TRUE(wait_for([&] { return sub.reader().alive_writers() == 0; }))
      << "alive writers " << sub.reader().alive_writers();
  EXPECT_EQ(sub.latest().header().source().to_string(), "killed_writer");
}

}  // namespace
}  // namespace teleop::transport
