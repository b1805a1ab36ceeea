#include "teleop/robot/hardware_registry.h"

#include <stdexcept>

namespace teleop::robot {

void HardwareRegistry::add(std::string name, Parser parser) {
  for (const auto& [known, ignored] : backends_) {
    if (known == name) throw std::logic_error("hardware backend " + name + " registered twice");
  }
  backends_.emplace_back(std::move(name), std::move(parser));
}

std::shared_ptr<const HardwareSpec> HardwareRegistry::parse(const ConfigNode& section) const {
  if (backends_.empty()) throw std::logic_error("no hardware backend registered");
  std::vector<std::string> names;
  for (const auto& [name, parser] : backends_) names.push_back(name);
  const std::string chosen = section.get_choice("hardware", names, names.front());
  for (const auto& [name, parser] : backends_) {
    if (name == chosen) return parser(section);
  }
  return nullptr;  // get_choice refused anything else
}

}  // namespace teleop::robot
