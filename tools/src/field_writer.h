#pragma once
// Writes a sample's fields as YAML while the walkers in sample_text.cpp visit them, or only the
// one field a dotted path selects.

#include <spdlog/fmt/fmt.h>

#include <string>
#include <string_view>
#include <vector>

namespace teleop::tools {

class FieldWriter {
 public:
  /// `filter`: a dotted path ("header.seq", "links[0].peer"); empty: every field.
  explicit FieldWriter(std::string filter) : filter_(std::move(filter)) {}

  /// Opens a nested struct named `name`.
  void begin(std::string_view name);
  /// Opens item `index` of a sequence of structs (the sequence opened with begin()).
  void begin_item(size_t index);
  void end();

  void value(std::string_view name, std::string_view text);
  void value(std::string_view name, double v) { value(name, std::string_view(number(v))); }
  void value(std::string_view name, int64_t v) { value(name, std::string_view(fmt::format("{}", v))); }
  void value(std::string_view name, uint64_t v) { value(name, std::string_view(fmt::format("{}", v))); }
  void value(std::string_view name, bool v) { value(name, std::string_view(v ? "true" : "false")); }
  /// A sequence of numbers (or of anything `format` turns into text) as a flow list.
  template <typename Seq, typename Format>
  void list(std::string_view name, const Seq& seq, Format format) {
    std::string text = "[";
    for (const auto& v : seq) text += (text.size() > 1 ? ", " : "") + std::string(format(v));
    value(name, std::string_view(text + "]"));
  }
  template <typename Seq>
  void list(std::string_view name, const Seq& seq) {
    list(name, seq, [](double v) { return number(v); });
  }

  /// The text written; for a filter, the selected field's value (its block for a struct).
  const std::string& text() const { return text_; }
  /// Whether the filter selected anything.
  bool matched() const { return matched_; }

  static std::string number(double v) { return fmt::format("{:.9g}", v); }

 private:
  std::string path_of(std::string_view name) const;
  // where a line of this path goes, relative to the filter: -1 not shown, else its indent level
  int level_of(const std::string& path) const;

  std::string filter_;
  std::vector<std::string> path_;   // the open structs, e.g. {"links", "[0]"}
  std::vector<bool> item_pending_;  // an item was opened and its first line not written yet
  std::string text_;
  bool matched_ = false;
};

}  // namespace teleop::tools
