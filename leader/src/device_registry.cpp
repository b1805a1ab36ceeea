#include "teleop/leader/device_registry.h"

#include <algorithm>
#include <stdexcept>

#include "teleop/common/did_you_mean.h"

namespace teleop::leader {

void DeviceRegistry::add(std::string name, Parser parser) {
  for (const auto& [known, ignored] : devices_) {
    if (known == name) throw std::logic_error("leader device " + name + " registered twice");
  }
  devices_.emplace_back(std::move(name), std::move(parser));
}

std::vector<std::string> DeviceRegistry::names() const {
  std::vector<std::string> names;
  for (const auto& [name, parser] : devices_) names.push_back(name);
  return names;
}

std::shared_ptr<const DeviceSpec> DeviceRegistry::parse(const ConfigNode& section) const {
  if (devices_.empty()) throw std::logic_error("no leader device registered");
  const std::vector<std::string> known = names();
  const std::string chosen = section.get_string("device", known.front());
  const auto entry = std::find_if(devices_.begin(), devices_.end(), [&](const auto& d) { return d.first == chosen; });
  if (entry == devices_.end()) {
    std::string list;
    for (const auto& name : known) list += (list.empty() ? "" : ", ") + name;
    throw section.error("device", "'" + chosen + "' is not one of: " + list + did_you_mean(chosen, known));
  }
  auto spec = entry->second(section);
  // the settings a file keeps for the devices it does not use are still checked (and read, so
  // they are no unknown keys): the shipped leader.yaml carries the haptic arm's beside `scripted`
  for (const auto& [name, parser] : devices_) {
    if (name != chosen && section.has(name)) parser(section);
  }
  return spec;
}

}  // namespace teleop::leader
