// The QoS profiles: the shipped file reproduces the code presets field by field, a replacement
// file (YAML key or FASTRTPS_DEFAULT_PROFILES_FILE) takes effect on the wire, the YAML keys
// override it, and a bad file is a ConfigError naming the file and the profile.

#include "teleop/transport/qos_profiles.h"

#include <fastrtps/xmlparser/XMLProfileManager.h>
#include <gtest/gtest.h>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>

#include "in_process_bus.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/qos.h"
#include "test_helpers.h"

namespace teleop::transport {
namespace {

namespace dds = eprosima::fastdds::dds;
using test::error_of;
using test::TempDir;

constexpr QosPreset kPresets[] = {QosPreset::kStream, QosPreset::kState, QosPreset::kEvent};

using test_bus::stream_topic;
using test_bus::wait_for;

ParticipantConfig config(const std::string& name, const std::string& profiles = "") {
  ParticipantConfig c = test_bus::config(name);
  c.qos_profiles = profiles;
  return c;
}

int64_t ns_of(const eprosima::fastrtps::Duration_t& d) {
  return static_cast<int64_t>(d.seconds) * 1'000'000'000 + static_cast<int64_t>(d.nanosec);
}

// the built-in profiles with one text replaced (it must be there exactly `count` times)
std::string builtin_with(const std::string& from, const std::string& to, int count) {
  std::string text(builtin_qos_profiles());
  int replaced = 0;
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
    ++replaced;
  }
  EXPECT_EQ(replaced, count) << from;
  return text;
}

// Sets an environment variable for one scope.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) { setenv(name, value.c_str(), 1); }
  ~ScopedEnv() { unsetenv(name_); }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
};

// Every field a code preset sets, compared one by one (the message names the profile).
template <typename Qos>
void expect_same_endpoint(const Qos& xml, const Qos& code, const std::string& what) {
  EXPECT_EQ(xml.reliability().kind, code.reliability().kind) << what;
  EXPECT_EQ(xml.reliability().max_blocking_time, code.reliability().max_blocking_time) << what;
  EXPECT_EQ(xml.durability().kind, code.durability().kind) << what;
  EXPECT_EQ(xml.history().kind, code.history().kind) << what;
  EXPECT_EQ(xml.history().depth, code.history().depth) << what;
  EXPECT_EQ(xml.deadline().period, code.deadline().period) << what;
  EXPECT_EQ(xml.liveliness().kind, code.liveliness().kind) << what;
  EXPECT_EQ(xml.liveliness().lease_duration, code.liveliness().lease_duration) << what;
  EXPECT_EQ(xml.liveliness().announcement_period, code.liveliness().announcement_period) << what;
  EXPECT_EQ(xml.resource_limits().max_samples, code.resource_limits().max_samples) << what;
  EXPECT_EQ(xml.resource_limits().max_instances, code.resource_limits().max_instances) << what;
  EXPECT_EQ(xml.resource_limits().max_samples_per_instance, code.resource_limits().max_samples_per_instance) << what;
  EXPECT_EQ(xml.resource_limits().allocated_samples, code.resource_limits().allocated_samples) << what;
  EXPECT_EQ(xml.resource_limits().extra_samples, code.resource_limits().extra_samples) << what;
  EXPECT_EQ(xml.data_sharing().kind(), code.data_sharing().kind()) << what;
  EXPECT_EQ(xml.endpoint().history_memory_policy, code.endpoint().history_memory_policy) << what;
}

void expect_same_writer(const dds::DataWriterQos& xml, const dds::DataWriterQos& code, const std::string& what) {
  expect_same_endpoint(xml, code, what);
  EXPECT_EQ(xml.publish_mode().kind, code.publish_mode().kind) << what;
  EXPECT_EQ(xml.reliable_writer_qos().times.heartbeatPeriod, code.reliable_writer_qos().times.heartbeatPeriod) << what;
  EXPECT_EQ(xml.reliable_writer_qos().times.nackResponseDelay, code.reliable_writer_qos().times.nackResponseDelay)
      << what;
}

void expect_presets_reproduced(Participant& p) {
  const ParticipantConfig defaults;  // no YAML override: the profiles alone
  for (QosPreset preset : kPresets) {
    expect_same_writer(p.endpoint_qos().writer(preset), writer_qos(preset, defaults), writer_profile_name(preset));
    expect_same_endpoint(p.endpoint_qos().reader(preset), reader_qos(preset, defaults), reader_profile_name(preset));
  }
  // the participant as created, not only its profile
  // copies: the preset is a temporary, a reference into it dangles (ASan: stack-use-after-scope)
  const auto created = p.dds()->get_qos().wire_protocol().builtin.discovery_config;
  const auto code = participant_qos_preset(defaults).wire_protocol().builtin.discovery_config;
  EXPECT_EQ(created.leaseDuration, code.leaseDuration);
  EXPECT_EQ(created.leaseDuration_announcementperiod, code.leaseDuration_announcementperiod);
}

TEST(QosProfiles, BuiltInProfilesReproduceTheCodePresetsFieldByField) {
  Participant p(config("builtin"));
  expect_presets_reproduced(p);
}

TEST(QosProfiles, ShippedFileReproducesTheCodePresetsFieldByField) {
  // the file a user copies, read from disk as a replacement would be
  Participant p(config("shipped", std::string(TELEOP_SOURCE_DIR) + "/config/qos/teleop_profiles.xml"));
  expect_presets_reproduced(p);
}

TEST(QosProfiles, YamlKeysOverrideTheProfiles) {
  TempDir dir("teleop_qos_profiles");
  ParticipantConfig c =
      config("overridden", dir.write("slow.xml", builtin_with("<nanosec>5000000<", "<nanosec>9000000<", 2)));
  c.liveliness_lease_ns = 400'000'000;
  c.participant_lease_ns = 6'000'000'000;
  c.stream_deadline_ns = 2'000'000;
  Participant p(c);
  for (QosPreset preset : kPresets) {
    EXPECT_EQ(ns_of(p.endpoint_qos().writer(preset).liveliness().lease_duration), 400'000'000) << to_string(preset);
    EXPECT_EQ(ns_of(p.endpoint_qos().writer(preset).liveliness().announcement_period), 400'000'000 / 3)
        << to_string(preset);
    EXPECT_EQ(ns_of(p.endpoint_qos().reader(preset).liveliness().lease_duration), 400'000'000) << to_string(preset);
  }
  EXPECT_EQ(ns_of(p.endpoint_qos().writer(QosPreset::kStream).deadline().period), 2'000'000);
  EXPECT_EQ(ns_of(p.endpoint_qos().reader(QosPreset::kStream).deadline().period), 2'000'000);
  const auto discovery = p.dds()->get_qos().wire_protocol().builtin.discovery_config;
  EXPECT_EQ(ns_of(discovery.leaseDuration), 6'000'000'000);
  EXPECT_EQ(ns_of(discovery.leaseDuration_announcementperiod), 2'000'000'000);
}

// One sample from a writer to a reader, then a silence of 200 ms: the number of deadlines the
// reader saw missed, after checking the deadline the reader checks; a stream's writer offers
// none on the wire (the reader checks it from arrivals, stream_freshness.h).
uint64_t deadlines_missed_in_silence(const std::string& profiles, const std::string& leaf, int64_t expected_ns) {
  test_bus::DiscoveredWriters offered;
  Participant writer_side(config("deadline_writer", profiles));
  Participant reader_side(config("deadline_reader", profiles), &offered);
  Writer<msg::JointState> writer = writer_side.make_writer(stream_topic(leaf));
  Reader<msg::JointState> reader = reader_side.make_reader(stream_topic(leaf));
  EXPECT_TRUE(wait_for([&] { return writer.matched() == 1 && reader.matched() == 1; }));
  EXPECT_EQ(reader.deadline_ns(), expected_ns);
  const auto offered_deadline = [&] {
    const auto writers = offered.by_topic();
    const auto it = writers.find(stream_topic(leaf).name);
    return it == writers.end() ? -1 : it->second.deadline_ns;
  };
  EXPECT_TRUE(wait_for([&] { return offered_deadline() == 0; })) << "offered " << offered_deadline();
  msg::JointState sample;
  EXPECT_TRUE(writer.write(sample));
  EXPECT_TRUE(wait_for([&] { return reader.take_next(sample); }));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  return reader.deadline_missed();
}

TEST(QosProfiles, StreamDeadlineFromAReplacementFileIsWhatReadersCheck) {
  // 5 ms shipped: a 200 ms silence misses it; 10 s from the file: it does not
  EXPECT_GT(deadlines_missed_in_silence("", "deadline_builtin", 5'000'000), 0u);
  TempDir dir("teleop_qos_profiles");
  const std::string file =
      dir.write("long.xml", builtin_with("<sec>0</sec><nanosec>5000000<", "<sec>10</sec><nanosec>0<", 2));
  EXPECT_EQ(deadlines_missed_in_silence(file, "deadline_xml", 10'000'000'000), 0u);
}

TEST(QosProfiles, DefaultProfilesFileOfTheEnvironmentReplacesTheBuiltInOnes) {
  TempDir dir("teleop_qos_profiles");
  ScopedEnv env(kProfilesFileEnv, dir.write("env.xml", builtin_with("<nanosec>5000000<", "<nanosec>3000000<", 2)));
  Participant p(config("env"));
  EXPECT_EQ(ns_of(p.endpoint_qos().writer(QosPreset::kStream).deadline().period), 3'000'000);
  EXPECT_EQ(ns_of(p.endpoint_qos().reader(QosPreset::kStream).deadline().period), 3'000'000);
}

TEST(QosProfiles, DefaultProfilesFileWithoutTeleopProfilesIsLeftToOtherPrograms) {
  TempDir dir("teleop_qos_profiles");
  ScopedEnv env(
      kProfilesFileEnv,
      dir.write("ros.xml",
                "<?xml version=\"1.0\"?>\n<dds xmlns=\"http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles\">"
                "<profiles><data_writer profile_name=\"some_ros_writer\"><qos><reliability><kind>RELIABLE"
                "</kind></reliability></qos></data_writer></profiles></dds>\n"));
  Participant p(config("env_other"));
  EXPECT_EQ(ns_of(p.endpoint_qos().writer(QosPreset::kStream).deadline().period), kDefaultStreamDeadlineNs);
}

TEST(QosProfiles, DefaultProfilesFileWithSomeTeleopProfilesIsAnError) {
  TempDir dir("teleop_qos_profiles");
  const std::string file = dir.write("partial.xml", builtin_with("teleop_state_reader", "my_state_reader", 1));
  ScopedEnv env(kProfilesFileEnv, file);
  EXPECT_EQ(error_of<ConfigError>([] { Participant p(config("env_partial")); }),
            file +
                ": teleop_state_reader: no data_reader profile of this name (a teleop QoS profiles file defines all "
                "seven profiles of config/qos/teleop_profiles.xml; a profile Fast DDS refused is missing too)");
}

TEST(QosProfiles, MissingProfileIsAConfigErrorNamingFileAndProfile) {
  TempDir dir("teleop_qos_profiles");
  const std::string file = dir.write("renamed.xml", builtin_with("teleop_event_writer", "event_writer", 1));
  const std::string message = error_of<ConfigError>([&] { Participant p(config("missing", file)); });
  EXPECT_EQ(message.rfind(file + ": teleop_event_writer: no data_writer profile of this name", 0), 0u) << message;
}

TEST(QosProfiles, MalformedXmlIsAConfigErrorNamingFileAndLine) {
  TempDir dir("teleop_qos_profiles");
  // the closing tag of the second line's element is misspelt
  const std::string file = dir.write("broken.xml", "<?xml version=\"1.0\"?>\n<dds><profiles></profile></dds>\n");
  const std::string message = error_of<ConfigError>([&] { Participant p(config("broken", file)); });
  EXPECT_EQ(message.rfind(file + ":2: malformed XML: ", 0), 0u) << message;
}

TEST(QosProfiles, ProfileFastDdsRefusesIsAConfigErrorNamingTheFile) {
  TempDir dir("teleop_qos_profiles");
  // well-formed XML, but no reliability kind Fast DDS knows
  const std::string file =
      dir.write("refused.xml", builtin_with("<kind>BEST_EFFORT</kind>", "<kind>SOMETIMES</kind>", 2));
  // Fast DDS refuses the whole file and logs why; the error names the first profile it refuses
  const std::string text(builtin_qos_profiles());
  const auto line = 1 + std::count(text.begin(), text.begin() + text.find("\"teleop_stream_writer\""), '\n');
  EXPECT_EQ(error_of<ConfigError>([&] { Participant p(config("refused", file)); }),
            file + ":" + std::to_string(line) +
                ": teleop_stream_writer: Fast DDS refused this data_writer profile (its XML parser logged why above)");
}

TEST(QosProfiles, MissingFileIsAConfigError) {
  const std::string file = "/nonexistent/teleop_profiles.xml";
  EXPECT_EQ(error_of<ConfigError>([&] { Participant p(config("nofile", file)); }),
            file + ": no such QoS profiles file (" + file + " (transport.qos_profiles))");
}

TEST(QosProfiles, LivelinessLeaseLongerThanTheParticipantLeaseIsAConfigError) {
  ParticipantConfig c = config("leases");
  c.liveliness_lease_ns = 5'000'000'000;  // the profiles' participant lease is 3 s
  EXPECT_EQ(error_of<ConfigError>([&] { Participant p(c); }),
            "config/qos/teleop_profiles.xml (built in): teleop_stream_writer: its liveliness lease (5000 ms) is longer "
            "than the participant lease (3000 ms; transport.*_lease_ms override the profiles)");
}

TEST(QosProfiles, IntraProcessDeliveryStaysOffWhateverTheProfilesSay) {
  TempDir dir("teleop_qos_profiles");
  const std::string full = "<library_settings><intraprocess_delivery>FULL</intraprocess_delivery></library_settings>";
  const std::string file = dir.write("intraprocess.xml", builtin_with("<profiles>", full + "<profiles>", 1));
  // Fast DDS itself applies the file's library settings when it loads it
  using eprosima::fastrtps::xmlparser::XMLProfileManager;
  ASSERT_EQ(dds::DomainParticipantFactory::get_instance()->load_XML_profiles_file(file),
            eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK);
  ASSERT_EQ(XMLProfileManager::library_settings().intraprocess_delivery, eprosima::fastrtps::INTRAPROCESS_FULL);
  Participant p(config("intraprocess", file));
  EXPECT_EQ(XMLProfileManager::library_settings().intraprocess_delivery, eprosima::fastrtps::INTRAPROCESS_OFF);
}

TEST(QosProfiles, ImpairedParticipantKeepsDataSharingOffWhateverTheProfilesSay) {
  TempDir dir("teleop_qos_profiles");
  ParticipantConfig c =
      config("impaired", dir.write("sharing.xml", builtin_with("<kind>OFF</kind>", "<kind>AUTOMATIC</kind>", 6)));
  c.shm = false;
  c.impairment.links.push_back({});
  c.impairment.links.back().to = "nobody";
  Participant p(c);
  for (QosPreset preset : kPresets) {
    EXPECT_EQ(p.endpoint_qos().writer(preset).data_sharing().kind(), dds::DataSharingKind::OFF) << to_string(preset);
    EXPECT_EQ(p.endpoint_qos().reader(preset).data_sharing().kind(), dds::DataSharingKind::OFF) << to_string(preset);
  }
}

}  // namespace
}  // namespace teleop::transport
