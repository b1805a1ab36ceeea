#pragma once
// What the walkers in sample_text.cpp hand a sample's fields to, in order: nested structs opened
// and closed, values as text. FieldWriter makes YAML of them (`topic echo`), FieldColumns the
// flat columns of a CSV row (`bag export`).

#include <spdlog/fmt/fmt.h>

#include <string>
#include <string_view>
#include <vector>

namespace teleop::tools {

/// The dotted path of field `name` inside the open structs `open` ({"links", "[0]"}, "peer" ->
/// "links[0].peer"); "" names the innermost open struct itself.
std::string dotted_path(const std::vector<std::string>& open, std::string_view name);

class FieldVisitor {
 public:
  virtual ~FieldVisitor() = default;

  /// Opens a nested struct named `name`.
  virtual void begin(std::string_view name) = 0;
  /// Opens item `index` of a sequence of structs (the sequence opened with begin()).
  virtual void begin_item(size_t index) = 0;
  virtual void end() = 0;
  virtual void value(std::string_view name, std::string_view text) = 0;
  /// A sequence of values, each as text.
  virtual void values(std::string_view name, const std::vector<std::string>& items) = 0;

  void value(std::string_view name, double v) { value(name, std::string_view(number(v))); }
  void value(std::string_view name, int64_t v) { value(name, std::string_view(fmt::format("{}", v))); }
  void value(std::string_view name, uint64_t v) { value(name, std::string_view(fmt::format("{}", v))); }
  void value(std::string_view name, bool v) { value(name, std::string_view(v ? "true" : "false")); }
  /// A sequence of numbers (or of anything `format` turns into text).
  template <typename Seq, typename Format>
  void list(std::string_view name, const Seq& seq, Format format) {
    std::vector<std::string> items;
    items.reserve(seq.size());
    for (const auto& v : seq) items.emplace_back(format(v));
    values(name, items);
  }
  template <typename Seq>
  void list(std::string_view name, const Seq& seq) {
    list(name, seq, [](double v) { return number(v); });
  }

  static std::string number(double v) { return fmt::format("{:.9g}", v); }
};

}  // namespace teleop::tools
