#include "teleop/common/config.h"

#include "teleop/common/did_you_mean.h"
#include "teleop/common/input_file.h"
#include "teleop/common/strict_yaml.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <sstream>

namespace teleop {

// every mapping read from one file, so that unused keys can be found at the end
struct ConfigNode::FileState {
  std::string file;
  std::vector<std::shared_ptr<MappingRecord>> mappings;
  // dotted key path -> the "--set KEY=VALUE" that put it there (its value and any mapping created
  // on the way), so errors about it point at the argument instead of a line of the file
  std::map<std::string, std::string> set_by;

  // the override that set `path` or one of its parents; nullptr when the file did
  const std::string* override_of(const std::string& path) const {
    for (std::string p = path;;) {
      if (auto it = set_by.find(p); it != set_by.end()) return &it->second;
      const auto dot = p.rfind('.');
      if (dot == std::string::npos) return nullptr;
      p.resize(dot);
    }
  }
};

struct ConfigNode::MappingRecord {
  YAML::Node node;
  std::string path;
  std::set<std::string> used;
};

namespace {

std::string format_number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

std::string describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar: return "'" + node.Scalar() + "'";
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Map: return "a mapping";
    case YAML::NodeType::Null: return "nothing";
    default: return "an undefined value";
  }
}

// the parsed document, every rule of strict_yaml.h kept; a top level that is not a mapping has no keys to read
YAML::Node parse_root(const std::string& text, const std::string& source) {
  YAML::Node root;
  try {
    root = parse_strict_yaml(text, source);
  } catch (const YAML::ParserException& e) {
    throw ConfigError(source + ":" + std::to_string(e.mark.line + 1) + ": malformed YAML: " + e.msg);
  } catch (const YAML::Exception& e) {
    throw ConfigError(source + ": not readable as YAML: " + e.msg);
  }
  if (!root.IsMap()) throw ConfigError(source + ": the top level must be a mapping of keys");
  return root;
}

}  // namespace

ConfigNode ConfigNode::load_file(const std::string& path) {
  // read first, as a regular file only: a FIFO or a device would block the parse or never end it
  const std::string text = read_input_file(path);
  return ConfigNode(std::make_shared<FileState>(FileState{path, {}, {}}), parse_root(text, path), "");
}

ConfigNode ConfigNode::load_string(const std::string& text, const std::string& source_name) {
  return ConfigNode(std::make_shared<FileState>(FileState{source_name, {}, {}}), parse_root(text, source_name), "");
}

void ConfigNode::apply_override(const std::string& spec) {
  const auto eq = spec.find('=');
  const std::string key = spec.substr(0, eq);
  if (eq == std::string::npos || key.empty() || eq + 1 == spec.size()) {
    throw ConfigError(state_->file + ": --set " + spec + ": expected KEY=VALUE, e.g. node.duration_s=5");
  }
  std::vector<std::string> segments;
  for (size_t begin = 0;;) {
    const auto dot = key.find('.', begin);
    segments.push_back(key.substr(begin, dot - begin));
    if (segments.back().empty())
      throw ConfigError(state_->file + ": --set " + spec + ": empty key segment in '" + key + "'");
    if (dot == std::string::npos) break;
    begin = dot + 1;
  }
  YAML::Node value;
  try {
    value = parse_strict_yaml(spec.substr(eq + 1), state_->file + " (--set " + spec + ")", key);
  } catch (const YAML::ParserException& e) {
    throw ConfigError(state_->file + ": --set " + spec + ": malformed YAML value: " + e.msg);
  }
  // walk (and where missing, create) the mappings down to the last segment; reset() re-seats the
  // handle, where operator= would overwrite the node it refers to
  YAML::Node mapping;
  mapping.reset(node_);
  std::string path = path_;
  for (size_t i = 0; i + 1 < segments.size(); ++i) {
    path = path.empty() ? segments[i] : path + "." + segments[i];
    YAML::Node next;
    next.reset(mapping[segments[i]]);
    if (!next.IsDefined() || next.IsNull()) {
      const YAML::Node created(YAML::NodeType::Map);
      mapping[segments[i]] = created;
      next.reset(created);
      state_->set_by.emplace(path, spec);
    } else if (!next.IsMap()) {
      throw ConfigError(state_->file + ": --set " + spec + ": " + path + " is " + describe(next) + ", not a mapping");
    }
    mapping.reset(next);
  }
  mapping[segments.back()] = value;
  state_->set_by[path.empty() ? segments.back() : path + "." + segments.back()] = spec;
}

ConfigNode::ConfigNode(std::shared_ptr<FileState> state, YAML::Node node, std::string path)
    : state_(std::move(state)), node_(node), path_(std::move(path)) {
  // a mapping opened again (e.g. child("a") called twice) shares its record, so that a key read
  // through either handle counts as used
  for (const auto& mapping : state_->mappings) {
    if (mapping->node.is(node_)) {
      record_ = mapping;
      return;
    }
  }
  record_ = std::make_shared<MappingRecord>(MappingRecord{node_, path_, {}});
  state_->mappings.push_back(record_);
}

const std::string& ConfigNode::file() const { return state_->file; }

std::string ConfigNode::key_path(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

std::string ConfigNode::location(const YAML::Mark& mark, const std::string& path) const {
  if (const std::string* spec = state_->override_of(path)) return state_->file + " (--set " + *spec + ")";
  return mark.line >= 0 ? state_->file + ":" + std::to_string(mark.line + 1) : state_->file;
}

ConfigError ConfigNode::error_at(const YAML::Node& where, const std::string& key,
                                 const std::string& problem) const {
  YAML::Mark mark = where.IsDefined() ? where.Mark() : node_.Mark();
  if (where.IsDefined() && where.IsNull()) {
    // a key without a value: yaml-cpp marks the empty value at the next token, often a later
    // line, so point at the key itself
    for (const auto& entry : node_) {
      if (entry.first.IsScalar() && entry.first.Scalar() == key) mark = entry.first.Mark();
    }
  }
  return ConfigError(location(mark, key_path(key)) + ": " + key_path(key) + ": " + problem);
}

ConfigError ConfigNode::error(const std::string& key, const std::string& problem) const {
  return error_at(lookup(key), key, problem);
}

YAML::Node ConfigNode::lookup(const std::string& key) const {
  // a const view, so a missing key does not get inserted
  const YAML::Node& view = node_;
  return view[key];
}

bool ConfigNode::has(const std::string& key) const {
  const YAML::Node n = lookup(key);
  return n.IsDefined() && !n.IsNull();
}

std::vector<std::string> ConfigNode::keys() const {
  std::vector<std::string> out;
  for (const auto& entry : node_) out.push_back(entry.first.as<std::string>());
  return out;
}

YAML::Node ConfigNode::require(const std::string& key) const {
  record_->used.insert(key);
  const YAML::Node n = lookup(key);
  if (!n.IsDefined()) throw error_at(node_, key, "missing required key");
  if (n.IsNull()) throw error_at(n, key, "has no value");
  return n;
}

template <typename T>
T ConfigNode::convert_scalar(const YAML::Node& node, const std::string& key, const char* type_name) const {
  T value{};
  if (!node.IsScalar() || !YAML::convert<T>::decode(node, value)) {
    throw error_at(node, key, std::string("expected ") + type_name + ", got " + describe(node));
  }
  return value;
}

void ConfigNode::check_range(const YAML::Node& node, const std::string& key, double value, Range range) const {
  if (!std::isfinite(value) || value < range.min || value > range.max) {
    throw error_at(node, key, "value " + node.Scalar() + " is out of range [" + format_number(range.min) + ", " +
                                  format_number(range.max) + "]");
  }
}

ConfigNode ConfigNode::make_child(const YAML::Node& node, const std::string& key) const {
  if (!node.IsMap()) throw error_at(node, key, "expected a mapping, got " + describe(node));
  return ConfigNode(state_, node, key_path(key));
}

ConfigNode ConfigNode::child(const std::string& key) const { return make_child(require(key), key); }

std::optional<ConfigNode> ConfigNode::optional_child(const std::string& key) const {
  if (!lookup(key).IsDefined()) return std::nullopt;
  return child(key);
}

std::string ConfigNode::get_string(const std::string& key) const {
  return convert_scalar<std::string>(require(key), key, "a string");
}

bool ConfigNode::get_bool(const std::string& key) const {
  return convert_scalar<bool>(require(key), key, "true or false");
}

int64_t ConfigNode::get_int(const std::string& key, Range range) const {
  const YAML::Node n = require(key);
  const auto value = convert_scalar<int64_t>(n, key, "an integer");
  check_range(n, key, static_cast<double>(value), range);
  return value;
}

double ConfigNode::get_double(const std::string& key, Range range) const {
  const YAML::Node n = require(key);
  const auto value = convert_scalar<double>(n, key, "a number");
  check_range(n, key, value, range);
  return value;
}

std::string ConfigNode::get_string(const std::string& key, const std::string& fallback) const {
  return lookup(key).IsDefined() ? get_string(key) : (record_->used.insert(key), fallback);
}

bool ConfigNode::get_bool(const std::string& key, bool fallback) const {
  return lookup(key).IsDefined() ? get_bool(key) : (record_->used.insert(key), fallback);
}

int64_t ConfigNode::get_int(const std::string& key, Range range, int64_t fallback) const {
  return lookup(key).IsDefined() ? get_int(key, range) : (record_->used.insert(key), fallback);
}

double ConfigNode::get_double(const std::string& key, Range range, double fallback) const {
  return lookup(key).IsDefined() ? get_double(key, range) : (record_->used.insert(key), fallback);
}

double ConfigNode::get_bound_or_off(const std::string& key, Range range, double fallback) const {
  const YAML::Node n = lookup(key);
  if (!n.IsDefined()) {
    record_->used.insert(key);
    return fallback;
  }
  if (n.IsScalar() && n.Scalar() == "off") {
    record_->used.insert(key);
    return std::numeric_limits<double>::infinity();
  }
  const YAML::Node value = require(key);
  const auto v = convert_scalar<double>(value, key, "a number or off");
  if (v == 0.0) throw error_at(value, key, "0 would switch the check off: write off if that is meant");
  check_range(value, key, v, range);
  return v;
}

std::string ConfigNode::get_yaml(const std::string& key) const {
  YAML::Emitter out;
  out << YAML::Flow << require(key);
  return out.c_str();
}

std::string ConfigNode::get_path(const std::string& key) const {
  const std::filesystem::path given(get_string(key));
  const std::filesystem::path path =
      given.is_absolute() ? given : std::filesystem::path(state_->file).parent_path() / given;
  if (!std::filesystem::is_regular_file(path)) {
    const std::string name = path.lexically_normal().string();
    // a FIFO or a device would block whoever opens it, or never end
    if (std::filesystem::exists(path)) {
      throw error_at(lookup(key), key, name + " is not a regular file (a folder, FIFO or device)");
    }
    throw error_at(lookup(key), key, "no file " + name);
  }
  return path.lexically_normal().string();
}

std::string ConfigNode::get_choice(const std::string& key, const std::vector<std::string>& choices) const {
  const std::string value = get_string(key);
  for (const auto& c : choices) {
    if (c == value) return value;
  }
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
  throw error_at(lookup(key), key, "'" + value + "' is not one of: " + list);
}

std::string ConfigNode::get_choice(const std::string& key, const std::vector<std::string>& choices,
                                   const std::string& fallback) const {
  return lookup(key).IsDefined() ? get_choice(key, choices) : (record_->used.insert(key), fallback);
}

std::vector<std::string> ConfigNode::get_string_list(const std::string& key) const {
  record_->used.insert(key);
  const YAML::Node n = lookup(key);
  if (!n.IsDefined() || n.IsNull()) return {};
  if (!n.IsSequence()) throw error_at(n, key, "expected a list of strings, got " + describe(n));
  std::vector<std::string> out;
  for (size_t i = 0; i < n.size(); ++i) {
    out.push_back(convert_scalar<std::string>(n[i], key + "[" + std::to_string(i) + "]", "a string"));
  }
  return out;
}

std::vector<double> ConfigNode::get_double_list(const std::string& key, Range range) const {
  record_->used.insert(key);
  const YAML::Node n = lookup(key);
  if (!n.IsDefined() || n.IsNull()) return {};
  if (!n.IsSequence()) throw error_at(n, key, "expected a list of numbers, got " + describe(n));
  std::vector<double> out;
  for (size_t i = 0; i < n.size(); ++i) {
    const std::string item_key = key + "[" + std::to_string(i) + "]";
    const auto value = convert_scalar<double>(n[i], item_key, "a number");
    check_range(n[i], item_key, value, range);
    out.push_back(value);
  }
  return out;
}

std::vector<ConfigNode> ConfigNode::get_node_list(const std::string& key) const {
  record_->used.insert(key);
  const YAML::Node n = lookup(key);
  if (!n.IsDefined() || n.IsNull()) return {};
  if (!n.IsSequence()) throw error_at(n, key, "expected a list of mappings, got " + describe(n));
  std::vector<ConfigNode> out;
  for (size_t i = 0; i < n.size(); ++i) out.push_back(make_child(n[i], key + "[" + std::to_string(i) + "]"));
  return out;
}

void ConfigNode::check_all_used() const {
  for (const auto& mapping : state_->mappings) {
    for (const auto& entry : mapping->node) {
      const auto key = entry.first.as<std::string>();
      if (mapping->used.count(key) == 0) {
        const std::string path = mapping->path.empty() ? key : mapping->path + "." + key;
        // the keys this mapping's parser asked for are the names it knows
        const std::vector<std::string> known(mapping->used.begin(), mapping->used.end());
        throw ConfigError(location(entry.first.Mark(), path) + ": " + path + ": unknown key" + did_you_mean(key, known));
      }
    }
  }
}

}  // namespace teleop
