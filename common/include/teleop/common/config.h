#pragma once
// Strict YAML configuration: every key read is checked for presence, type and range, and every
// key present must have been read. Errors name the file, the line, the key path and the problem.

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace teleop {

/// Bad configuration. The message is one line: "<file>:<line>: <key.path>: <problem>".
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Inclusive numeric range for validation.
struct Range {
  double min;
  double max;
};

/// A mapping in a YAML file. Reading a key marks it as used; `check_all_used()` on the root
/// then reports the first key nobody read (an unknown or misspelt key).
/// Configuration time only: allocates and throws ConfigError.
class ConfigNode {
 public:
  /// Parses a YAML file whose top level must be a mapping. Every failure (no such file, a
  /// folder, unreadable, malformed YAML, a key that is not a plain scalar, a key given twice in
  /// one mapping) throws ConfigError naming the file (and line).
  static ConfigNode load_file(const std::string& path);
  /// Parses YAML text; `source_name` stands in for the file name in errors.
  static ConfigNode load_string(const std::string& text, const std::string& source_name);

  /// Applies a command-line override "KEY=VALUE" (e.g. from `--set`) to this mapping before
  /// anything is read: KEY is a dotted path (missing mappings on the way are created), VALUE is
  /// parsed as YAML (a scalar, `[1, 2]`, `{a: 1}`). Errors about keys set this way (unknown key,
  /// bad value) name the `--set` argument instead of a line. Throws ConfigError on a malformed spec
  /// or when the path runs through a value that is not a mapping.
  void apply_override(const std::string& spec);

  /// A required nested mapping.
  ConfigNode child(const std::string& key) const;
  /// An optional nested mapping; nullopt when absent.
  std::optional<ConfigNode> optional_child(const std::string& key) const;
  bool has(const std::string& key) const;
  /// The keys of this mapping in file order (for free-form mappings such as named counters).
  std::vector<std::string> keys() const;

  /// Required scalars. Numbers may be range-checked.
  std::string get_string(const std::string& key) const;
  bool get_bool(const std::string& key) const;
  int64_t get_int(const std::string& key, Range range) const;
  double get_double(const std::string& key, Range range) const;

  /// Optional scalars with a default when the key is absent (present but wrong is an error).
  std::string get_string(const std::string& key, const std::string& fallback) const;
  bool get_bool(const std::string& key, bool fallback) const;
  int64_t get_int(const std::string& key, Range range, int64_t fallback) const;
  double get_double(const std::string& key, Range range, double fallback) const;

  /// Optional bound of a safety check: a number in `range` (whose minimum is above 0), or `off`,
  /// which returns +infinity (no bound). A 0 is refused with a hint to write `off`: a check is
  /// never switched off by a number.
  double get_bound_or_off(const std::string& key, Range range, double fallback) const;

  /// The value of a required key as one line of YAML in flow style (`abc`, `[1, 2]`, `{a: 1}`),
  /// for passing it on unparsed (e.g. as a `--set` argument).
  std::string get_yaml(const std::string& key) const;

  /// Required path of an existing file, resolved relative to this config file's folder.
  std::string get_path(const std::string& key) const;

  /// Required string that must be one of `choices`.
  std::string get_choice(const std::string& key, const std::vector<std::string>& choices) const;
  std::string get_choice(const std::string& key, const std::vector<std::string>& choices,
                         const std::string& fallback) const;

  /// Optional sequences (empty when absent).
  std::vector<std::string> get_string_list(const std::string& key) const;
  std::vector<double> get_double_list(const std::string& key, Range range) const;
  /// Sequence of mappings (empty when absent).
  std::vector<ConfigNode> get_node_list(const std::string& key) const;

  /// Throws for the first key anywhere in this file that was never read.
  void check_all_used() const;

  /// Builds an error for `key` of this mapping ("<file>:<line>: <path.key>: <problem>").
  ConfigError error(const std::string& key, const std::string& problem) const;

  const std::string& file() const;
  /// Dotted path of this mapping ("" for the root).
  const std::string& path() const { return path_; }

 private:
  struct FileState;
  struct MappingRecord;

  ConfigNode(std::shared_ptr<FileState> state, YAML::Node node, std::string path);
  YAML::Node lookup(const std::string& key) const;
  YAML::Node require(const std::string& key) const;
  std::string key_path(const std::string& key) const;
  std::string location(const YAML::Mark& mark, const std::string& path) const;
  ConfigError error_at(const YAML::Node& where, const std::string& key, const std::string& problem) const;
  ConfigNode make_child(const YAML::Node& node, const std::string& key) const;
  template <typename T>
  T convert_scalar(const YAML::Node& node, const std::string& key, const char* type_name) const;
  void check_range(const YAML::Node& node, const std::string& key, double value, Range range) const;

  std::shared_ptr<FileState> state_;
  std::shared_ptr<MappingRecord> record_;
  YAML::Node node_;
  std::string path_;
};

}  // namespace teleop
