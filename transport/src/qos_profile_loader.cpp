#include "qos_profile_loader.h"

#include <fastrtps/xmlparser/XMLProfileManager.h>
#include <tinyxml2.h>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string_view>
#include <vector>

namespace teleop::transport {
namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::types::ReturnCode_t;
using eprosima::fastrtps::xmlparser::XMLP_ret;
using eprosima::fastrtps::xmlparser::XMLProfileManager;

namespace {

constexpr QosPreset kPresets[] = {QosPreset::kStream, QosPreset::kState, QosPreset::kEvent};
constexpr const char* kBuiltinFile = "config/qos/teleop_profiles.xml";

std::mutex& registry_mutex() {
  static std::mutex mutex;
  return mutex;
}

int64_t ns_of(const eprosima::fastrtps::Duration_t& d) {
  return static_cast<int64_t>(d.seconds) * 1'000'000'000 + static_cast<int64_t>(d.nanosec);
}

// The teleop profiles the registry lacks, as "<kind> profile '<name>'".
std::vector<std::string> missing_profiles() {
  std::vector<std::string> missing;
  eprosima::fastrtps::ParticipantAttributes participant;
  if (XMLProfileManager::fillParticipantAttributes(kParticipantProfile, participant, false) != XMLP_ret::XML_OK) {
    missing.push_back(kParticipantProfile);
  }
  for (QosPreset preset : kPresets) {
    eprosima::fastrtps::PublisherAttributes writer;
    if (XMLProfileManager::fillPublisherAttributes(writer_profile_name(preset), writer, false) != XMLP_ret::XML_OK) {
      missing.push_back(writer_profile_name(preset));
    }
    eprosima::fastrtps::SubscriberAttributes reader;
    if (XMLProfileManager::fillSubscriberAttributes(reader_profile_name(preset), reader, false) != XMLP_ret::XML_OK) {
      missing.push_back(reader_profile_name(preset));
    }
  }
  return missing;
}

std::string kind_of(const std::string& profile) {
  if (profile == kParticipantProfile) return "participant";
  return profile.ends_with("_writer") ? "data_writer" : "data_reader";
}

// Intra-process delivery hands samples from a writer straight into same-process readers: it
// allocates on the writer's (control) thread in Fast DDS 2.9 and bypasses the transports that
// traffic is observed and impaired in. Nodes are separate processes, so nothing is lost. It is a
// library setting a profiles file may carry (<library_settings>): checked after every load, and
// written only when a file changed it, since other participants' Fast DDS threads read it.
void disable_intraprocess_delivery() {
  eprosima::fastrtps::LibrarySettingsAttributes settings = XMLProfileManager::library_settings();
  if (settings.intraprocess_delivery == eprosima::fastrtps::INTRAPROCESS_OFF) return;
  settings.intraprocess_delivery = eprosima::fastrtps::INTRAPROCESS_OFF;
  XMLProfileManager::library_settings(settings);
}

// The first profile of `doc` that Fast DDS refuses on its own (Fast DDS refuses a whole file
// for one bad profile and only logs which): the profiles are loaded one by one, in order.
struct RefusedProfile {
  int line = 0;
  std::string name;
  std::string kind;
};
std::optional<RefusedProfile> first_refused_profile(const tinyxml2::XMLDocument& doc) {
  const tinyxml2::XMLElement* root = doc.RootElement();
  if (root == nullptr) return std::nullopt;
  const tinyxml2::XMLElement* profiles =
      std::string_view(root->Name()) == "profiles" ? root : root->FirstChildElement("profiles");
  if (profiles == nullptr) return std::nullopt;
  XMLProfileManager::DeleteInstance();
  for (const auto* e = profiles->FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
    tinyxml2::XMLPrinter printer;
    e->Accept(&printer);
    const std::string text = std::string(
                                 "<dds xmlns=\"http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles\">"
                                 "<profiles>") +
                             printer.CStr() + "</profiles></dds>";
    if (dds::DomainParticipantFactory::get_instance()->load_XML_profiles_string(text.data(), text.size()) !=
        ReturnCode_t::RETCODE_OK) {
      const char* name = e->Attribute("profile_name");
      return RefusedProfile{e->GetLineNum(), name != nullptr ? name : "", e->Name()};
    }
  }
  return std::nullopt;
}

}  // namespace

const char* writer_profile_name(QosPreset preset) {
  static constexpr const char* kNames[] = {"teleop_stream_writer", "teleop_state_writer", "teleop_event_writer"};
  return kNames[static_cast<size_t>(preset)];
}

const char* reader_profile_name(QosPreset preset) {
  static constexpr const char* kNames[] = {"teleop_stream_reader", "teleop_state_reader", "teleop_event_reader"};
  return kNames[static_cast<size_t>(preset)];
}

QosProfileLoader::QosProfileLoader(const ParticipantConfig& config)
    : registry_lock_(registry_mutex()), config_(config) {
  auto* factory = dds::DomainParticipantFactory::get_instance();
  // Fast DDS loads its default file (FASTRTPS_DEFAULT_PROFILES_FILE) once, on first use: now,
  // before the registry is emptied, rather than later on top of this participant's profiles
  factory->load_profiles();
  XMLProfileManager::DeleteInstance();
  const char* env = std::getenv(kProfilesFileEnv);
  if (!config.qos_profiles.empty()) {
    source_ = config.qos_profiles + " (transport.qos_profiles)";
    load(config.qos_profiles);
  } else if (env != nullptr && *env != '\0') {
    // a default profiles file may be there for other Fast DDS programs (a ROS 2 system): it is
    // teleop's only if it defines the teleop profiles, and then all of them
    source_ = std::string(env) + " (" + kProfilesFileEnv + ")";
    load(env);
    if (missing_profiles().size() == 1 + 2 * std::size(kPresets)) {
      XMLProfileManager::DeleteInstance();
      load_builtin();
    }
  } else {
    load_builtin();
  }
  const auto missing = missing_profiles();
  if (!missing.empty()) {
    throw error(missing.front(), "no " + kind_of(missing.front()) +
                                     " profile of this name (a teleop QoS profiles file defines all seven profiles "
                                     "of config/qos/teleop_profiles.xml; a profile Fast DDS refused is missing too)");
  }
  disable_intraprocess_delivery();
}

QosProfileLoader::~QosProfileLoader() { XMLProfileManager::DeleteInstance(); }

ConfigError QosProfileLoader::error(const std::string& key, const std::string& problem) const {
  return ConfigError(file_ + ": " + (key.empty() ? "" : key + ": ") + problem);
}

void QosProfileLoader::load(const std::string& file) {
  file_ = file;
  if (!std::filesystem::is_regular_file(file)) throw error("", "no such QoS profiles file (" + source_ + ")");
  // Fast DDS only logs why it refuses a file; a parse of our own names the line
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(file.c_str()) != tinyxml2::XML_SUCCESS) {
    throw ConfigError(file + ":" + std::to_string(doc.ErrorLineNum()) + ": malformed XML: " + doc.ErrorStr());
  }
  if (dds::DomainParticipantFactory::get_instance()->load_XML_profiles_file(file) != ReturnCode_t::RETCODE_OK) {
    if (const auto refused = first_refused_profile(doc)) {
      throw ConfigError(file + ":" + std::to_string(refused->line) + ": " + refused->name + ": Fast DDS refused this " +
                        refused->kind + " profile (its XML parser logged why above)");
    }
    throw error("", "Fast DDS refused the QoS profiles file (its XML parser logged why above)");
  }
}

void QosProfileLoader::load_builtin() {
  file_ = std::string(kBuiltinFile) + " (built in)";
  source_ = file_;
  const std::string_view text = builtin_qos_profiles();
  if (dds::DomainParticipantFactory::get_instance()->load_XML_profiles_string(text.data(), text.size()) !=
      ReturnCode_t::RETCODE_OK) {
    throw error("", "Fast DDS refused the built-in QoS profiles (its XML parser logged why above)");
  }
}

dds::DomainParticipantQos QosProfileLoader::participant_qos() const {
  dds::DomainParticipantQos qos;
  if (dds::DomainParticipantFactory::get_instance()->get_participant_qos_from_profile(kParticipantProfile, qos) !=
      ReturnCode_t::RETCODE_OK) {
    throw error(kParticipantProfile, "no participant profile of this name");
  }
  apply_overrides(qos, config_);
  return qos;
}

EndpointQos QosProfileLoader::endpoint_qos(dds::Publisher& publisher, dds::Subscriber& subscriber,
                                           const dds::DomainParticipantQos& participant) const {
  EndpointQos qos;
  const int64_t participant_lease_ns = ns_of(participant.wire_protocol().builtin.discovery_config.leaseDuration);
  for (QosPreset preset : kPresets) {
    auto& writer = qos.writers[static_cast<size_t>(preset)];
    if (publisher.get_datawriter_qos_from_profile(writer_profile_name(preset), writer) != ReturnCode_t::RETCODE_OK) {
      throw error(writer_profile_name(preset), "no data_writer profile of this name");
    }
    apply_overrides(writer, preset, config_);
    auto& reader = qos.readers[static_cast<size_t>(preset)];
    if (subscriber.get_datareader_qos_from_profile(reader_profile_name(preset), reader) != ReturnCode_t::RETCODE_OK) {
      throw error(reader_profile_name(preset), "no data_reader profile of this name");
    }
    apply_overrides(reader, preset, config_);
    // a peer's participant would be dropped while its writers still count as alive
    const int64_t lease_ns = ns_of(writer.liveliness().lease_duration);
    const bool infinite = writer.liveliness().lease_duration == eprosima::fastrtps::c_TimeInfinite;
    if (!infinite && participant_lease_ns < lease_ns) {
      throw error(writer_profile_name(preset), "its liveliness lease (" + std::to_string(lease_ns / 1'000'000) +
                                                   " ms) is longer than the participant lease (" +
                                                   std::to_string(participant_lease_ns / 1'000'000) +
                                                   " ms; transport.*_lease_ms override the profiles)");
    }
  }
  return qos;
}

}  // namespace teleop::transport
