// `leader.device: plugin`: the library loaded and its table checked while the configuration is
// read (a wrong library is a configuration error), the device opened when the node starts: by
// default in a process of its own (isolation: process, isolated_plugin_device.h), so that a
// vendor SDK that crashes does not take the leader with it; in the leader's (in_process) where
// one less period of latency matters more.
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "isolated_plugin_device.h"
#include "plugin_device.h"
#include "teleop/common/data_paths.h"
#include "teleop/leader/device_registry.h"

namespace teleop::leader {
namespace {

// how the device is hosted: isolation and the host's timeout (in_process: none)
struct Hosting {
  bool isolated = true;
  double host_timeout_s = 0.05;
};

// teleop_device_host beside the running executable (both in <prefix>/bin, or a build's bin/)
std::string device_host() {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? "teleop_device_host" : (self.parent_path() / "teleop_device_host").string();
}

class PluginSpec final : public DeviceSpec {
 public:
  PluginSpec(std::shared_ptr<const PluginLibrary> library, PluginSettings settings, Hosting hosting)
      : library_(std::move(library)), settings_(std::move(settings)), hosting_(hosting) {}
  const char* device() const override { return "plugin"; }
  bool cartesian() const override { return library_->cartesian(); }
  std::unique_ptr<LeaderDevice> make(const DeviceSetup& setup) const override {
    if (!hosting_.isolated) return std::make_unique<PluginDevice>(library_, settings_, setup.period_s, setup.joints);
    return std::make_unique<IsolatedPluginDevice>(HostedPluginConfig{library_->path(), settings_, setup.period_s, setup.joints,
                                                                     library_->cartesian(), hosting_.host_timeout_s,
                                                                     device_host()});
  }

 private:
  std::shared_ptr<const PluginLibrary> library_;
  PluginSettings settings_;
  Hosting hosting_;
};

// A plugin's name ("simulated_delta"): libteleop_<name>.so where teleop's plugins are, beside the
// running executable (<prefix>/lib/teleop/plugins) or in this build tree; else "" (a library name
// for dlopen's own search, "libomega_teleop.so")
std::string find_named_plugin(const std::string& name) {
  const std::string file = "libteleop_" + name + ".so";
  const std::filesystem::path prefix = DataRoots::current().beside_executable.parent_path().parent_path();
  for (const std::filesystem::path& folder : {prefix / TELEOP_PLUGIN_DIR, std::filesystem::path(TELEOP_BUILD_PLUGIN_DIR)}) {
    std::error_code ec;
    if (std::filesystem::is_regular_file(folder / file, ec)) return (folder / file).lexically_normal().string();
  }
  return "";
}

}  // namespace

std::shared_ptr<const DeviceSpec> parse_plugin_device(const ConfigNode& leader_section) {
  const ConfigNode s = leader_section.child("plugin");
  // a path is the file's (relative to the config); a name is one of teleop's plugins, or
  // dlopen's to find
  const std::string given = s.get_string("library");
  std::string library = given.find('/') != std::string::npos ? s.get_path("library") : find_named_plugin(given);
  if (library.empty()) library = given;
  PluginSettings settings;
  if (const auto values = s.optional_child("settings")) {
    for (const std::string& key : values->keys()) settings.emplace_back(key, values->get_string(key));
  }
  Hosting hosting;
  const std::string isolation = s.get_string("isolation", "process");
  if (isolation != "process" && isolation != "in_process") throw s.error("isolation", "is process or in_process, not '" + isolation + "'");
  hosting.isolated = isolation == "process";
  hosting.host_timeout_s = s.get_double("host_timeout_ms", Range{1, 10000}, 50) * 1e-3;
  try {
    return std::make_shared<PluginSpec>(std::make_shared<const PluginLibrary>(library), std::move(settings), hosting);
  } catch (const std::runtime_error& e) {
    throw s.error("library", e.what());
  }
}

}  // namespace teleop::leader
