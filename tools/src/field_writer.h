#pragma once
// Writes a sample's fields as YAML while the walkers in sample_text.cpp visit them, or only the
// one field a dotted path selects.

#include <string>
#include <string_view>
#include <vector>

#include "field_visitor.h"

namespace teleop::tools {

class FieldWriter final : public FieldVisitor {
 public:
  /// `filter`: a dotted path ("header.seq", "links[0].peer"); empty: every field.
  explicit FieldWriter(std::string filter) : filter_(std::move(filter)) {}

  using FieldVisitor::value;
  void begin(std::string_view name) override;
  void begin_item(size_t index) override;
  void end() override;
  void value(std::string_view name, std::string_view text) override;
  /// As a flow list, "[1, 2, 3]".
  void values(std::string_view name, const std::vector<std::string>& items) override;

  /// The text written; for a filter, the selected field's value (its block for a struct).
  const std::string& text() const { return text_; }
  /// Whether the filter selected anything.
  bool matched() const { return matched_; }

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
