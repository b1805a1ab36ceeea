#pragma once
// A sample's fields as the flat columns of a CSV row while the walkers in sample_text.cpp visit
// them: each named by its dotted path, a sequence's items as name[i] ("q_rad[0]").

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "field_visitor.h"

namespace teleop::tools {

class FieldColumns final : public FieldVisitor {
 public:
  using FieldVisitor::value;
  void begin(std::string_view name) override { open_.emplace_back(name); }
  void begin_item(size_t index) override { open_.push_back(fmt::format("[{}]", index)); }
  void end() override { open_.pop_back(); }
  void value(std::string_view name, std::string_view text) override {
    columns_.emplace_back(dotted_path(open_, name), std::string(text));
  }
  void values(std::string_view name, const std::vector<std::string>& items) override {
    for (size_t i = 0; i < items.size(); ++i) columns_.emplace_back(dotted_path(open_, fmt::format("{}[{}]", name, i)), items[i]);
  }

  /// (column name, value as text), in the walkers' order.
  std::vector<std::pair<std::string, std::string>>& columns() { return columns_; }

 private:
  std::vector<std::string> open_;
  std::vector<std::pair<std::string, std::string>> columns_;
};

}  // namespace teleop::tools
