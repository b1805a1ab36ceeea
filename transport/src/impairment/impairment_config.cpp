#include "teleop/transport/impairment/impairment_config.h"

#include <filesystem>
#include <set>

#include "teleop/common/data_paths.h"

namespace teleop::transport::impairment {
namespace fs = std::filesystem;

std::string resolve_profile_path(const std::string& profile, const std::string& base_file) {
  const fs::path base = fs::path(base_file).parent_path();
  const fs::path given(profile);
  for (const fs::path& candidate : {given, base / given, base / "../network" / (profile + ".yaml"),
                                    base / "network" / (profile + ".yaml")}) {
    if (fs::is_regular_file(candidate)) return candidate.lexically_normal().string();
  }
  // a node config outside any config/ tree (a user's own folder) still names the shipped profiles
  return find_named_config("network", profile).string();
}

ImpairmentConfig parse_impairment_config(const ConfigNode& section) {
  ImpairmentConfig c;
  c.seed = static_cast<uint64_t>(section.get_int("seed", Range{0, 9.0e15}, 1));
  c.exclude_discovery = section.get_choice("scope", {"all", "exclude_discovery"}, "all") == "exclude_discovery";
  std::set<std::string> seen;
  for (const ConfigNode& link : section.get_node_list("links")) {
    LinkConfig l;
    l.to = link.get_string("to");
    if (!seen.insert(l.to).second) throw link.error("to", "'" + l.to + "' has two links");
    const std::string profile = link.get_string("profile");
    const std::string path = resolve_profile_path(profile, section.file());
    if (path.empty()) throw link.error("profile", "no profile file '" + profile + "' (nor network/" + profile + ".yaml)");
    l.profile = load_link_profile(path);
    c.links.push_back(std::move(l));
  }
  return c;
}

}  // namespace teleop::transport::impairment
