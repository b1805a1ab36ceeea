// libFuzzer target for what every node reads before it joins the network: the strict YAML reader
// (teleop::ConfigNode) and each node's configuration parser, the way run_node calls them
// (node and transport sections, the role's sections, then "every key read"). A parser may refuse
// its input only with a ConfigError (a node exits 2 naming file and key); any other exception, a
// crash, a leak or undefined behaviour is a finding.
//
// Each input is also given as a `--set` value. The seed corpus is the shipped node configs, an
// alias bomb and a config with anchors (seeds/). The node configs name model files and recordings
// relative to themselves; the fuzzer's configs live in a scratch folder beside minimal stand-ins of
// those files (a model that compiles, a recording with the right columns), so that parsing goes on
// past the paths into the rest of each section.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "teleop/common/config.h"
#include "teleop/follower/follower_config.h"
#include "teleop/hand/hand_config.h"
#include "leader_config.h"
#include "teleop/runtime/node_config.h"
#include "teleop/transport/participant_config.h"
#include "twin_config.h"

namespace {

namespace fs = std::filesystem;

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

fs::path scratch_dir() { return fs::temp_directory_path() / ("teleop_config_fuzz_" + std::to_string(getpid())); }

// the scratch folder: <dir>/nodes/fuzz.yaml is where each input "is", models and recordings beside
// it; removed when the fuzzer exits
std::string make_scratch() {
  const fs::path dir = scratch_dir();
  std::atexit([] {
    std::error_code ignored;
    fs::remove_all(scratch_dir(), ignored);
  });
  for (const char* model : {"panda", "scene_wall", "scene_box_shelf", "left_arm", "right_arm"}) {
    write(dir / "models" / (std::string(model) + ".xml"), "<mujoco model=\"stand_in\"/>\n");
  }
  std::string header = "t_s";
  for (const char* prefix : {"q_", "tau_op_"}) {
    for (int j = 0; j < 7; ++j) header += "," + std::string(prefix) + std::to_string(j);
  }
  std::string rows;
  for (int r = 0; r < 3; ++r) {
    rows += std::to_string(0.01 * r);
    for (int j = 0; j < 14; ++j) rows += ",0.0";
    rows += "\n";
  }
  for (const char* side : {"left", "right"}) write(dir / "trajectories" / ("box_task_" + std::string(side) + ".csv"), header + "\n" + rows);
  return (dir / "nodes" / "fuzz.yaml").string();
}

const std::string& source_name() {
  static const std::string name = make_scratch();
  return name;
}

// `read` may refuse its input only with a ConfigError (a message naming file and key: what a node
// does with bad input); anything else is a finding
void refused_only_with_config_error(const std::string& reader, const std::function<void()>& read) {
  try {
    read();
  } catch (const teleop::ConfigError&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s threw something else than ConfigError: %s\n", reader.c_str(), e.what());
    std::abort();
  }
}

// what run_node reads for one role (node_runner.cpp, load_setup)
void read_like_a_node(const std::string& text, const std::string& role,
                      const std::function<void(const teleop::ConfigNode&)>& parse_role) {
  refused_only_with_config_error(role + " config parser", [&] {
    const teleop::ConfigNode root = teleop::ConfigNode::load_string(text, source_name());
    teleop::runtime::parse_node_config(root.child("node"), role);
    teleop::transport::parse_participant_config(root.child("transport"), role);
    parse_role(root);
    root.check_all_used();
  });
}

// the same text as the value of a `--set KEY=VALUE` (a YAML document of its own: aliases and all)
void read_like_a_set_value(const std::string& text) {
  refused_only_with_config_error("--set", [&] {
    teleop::ConfigNode root = teleop::ConfigNode::load_string("node: {name: x}\n", source_name());
    root.apply_override("node.value=" + text);
  });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  read_like_a_node(text, "leader", [](const teleop::ConfigNode& root) { teleop::leader::parse_leader_arms(root); });
  read_like_a_node(text, "follower", [](const teleop::ConfigNode& root) { teleop::follower::parse_follower_arms(root); });
  read_like_a_node(text, "twin", [](const teleop::ConfigNode& root) { teleop::twin::parse_twin_arms(root); });
  read_like_a_node(text, "hand", [](const teleop::ConfigNode& root) { teleop::hand::parse_hand_config(root); });
  read_like_a_set_value(text);
  return 0;
}
