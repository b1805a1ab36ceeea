#include "teleop/tools/recording_traces.h"

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "deserialized.h"
#include "teleop/bag/bag_reader.h"

namespace teleop::tools {
namespace {

namespace fs = std::filesystem;

struct ArmSample {
  int64_t recv_ns = 0;
  std::string arm;
  std::vector<double> q;
};

// the joint states of one topic, in the recording's order; undecodable ones are left out
std::vector<ArmSample> read_joint_states(bag::BagReader& reader, int topic_id) {
  std::vector<ArmSample> samples;
  reader.select({topic_id});
  bag::BagMessage m;
  while (reader.next(m)) {
    try {
      const auto s = deserialized<msg::JointState>(m.data);
      samples.push_back({m.recv_ns, s.arm().c_str(), s.q_rad()});
    } catch (const std::runtime_error&) {
      continue;  // bytes of no joint state: nothing to pose from
    }
  }
  return samples;
}

// the arms in order of first appearance, each with its joint count
std::vector<std::pair<std::string, size_t>> arms_of(const std::vector<ArmSample>& samples) {
  std::vector<std::pair<std::string, size_t>> arms;
  for (const ArmSample& s : samples) {
    const auto seen = [&](const auto& a) { return a.first == s.arm; };
    if (std::none_of(arms.begin(), arms.end(), seen)) arms.emplace_back(s.arm, s.q.size());
  }
  return arms;
}

void write_trace(const std::vector<ArmSample>& samples, int64_t start_ns, const std::string& path) {
  const auto arms = arms_of(samples);
  std::ofstream out(path);
  out << "t_s,wall_s";
  for (const auto& [arm, joints] : arms) {
    for (size_t j = 0; j < joints; ++j) out << ',' << (arms.size() > 1 ? arm + "_" : "") << "q_" << j;
  }
  out << '\n';
  std::vector<const std::vector<double>*> latest(arms.size(), nullptr);
  for (const ArmSample& s : samples) {
    const auto at = std::find_if(arms.begin(), arms.end(), [&](const auto& a) { return a.first == s.arm; });
    latest[static_cast<size_t>(at - arms.begin())] = &s.q;
    if (std::count(latest.begin(), latest.end(), nullptr) > 0) continue;  // an arm not seen yet
    out << fmt::format("{:.6f},{:.6f}", static_cast<double>(s.recv_ns - start_ns) * 1e-9,
                       static_cast<double>(s.recv_ns) * 1e-9);
    for (size_t a = 0; a < arms.size(); ++a) {
      for (size_t j = 0; j < arms[a].second; ++j) {
        out << ',' << (j < latest[a]->size() ? fmt::format("{:.9g}", (*latest[a])[j]) : std::string("nan"));
      }
    }
    out << '\n';
  }
  out.close();
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace

std::vector<std::string> write_recording_traces(const std::string& recording, const std::string& out_dir) {
  bag::BagReader reader(recording);
  if (reader.topic_id("teleop/follower/joint_state") < 0) {
    throw std::runtime_error(recording + ": no teleop/follower/joint_state to pose the robot from");
  }
  fs::create_directories(out_dir);
  std::vector<std::string> written;
  for (const char* node : {"follower", "twin", "leader"}) {
    const int id = reader.topic_id(fmt::format("teleop/{}/joint_state", node));
    if (id < 0) continue;
    const std::vector<ArmSample> samples = read_joint_states(reader, id);
    if (samples.empty()) continue;
    written.push_back((fs::path(out_dir) / (std::string(node) + ".csv")).string());
    write_trace(samples, reader.start_ns(), written.back());
  }
  if (written.empty() || fs::path(written.front()).stem() != "follower") {
    throw std::runtime_error(recording + ": teleop/follower/joint_state holds no joint state");
  }
  return written;
}

}  // namespace teleop::tools
