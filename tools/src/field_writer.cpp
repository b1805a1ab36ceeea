#include "field_writer.h"

namespace teleop::tools {

std::string dotted_path(const std::vector<std::string>& open, std::string_view name) {
  std::string path;
  for (const std::string& p : open) path += (path.empty() || p.front() == '[' ? "" : ".") + p;
  if (!name.empty()) path += (path.empty() || name.front() == '[' ? "" : ".") + std::string(name);
  return path;
}

std::string FieldWriter::path_of(std::string_view name) const { return dotted_path(path_, name); }

int FieldWriter::level_of(const std::string& path) const {
  const auto depth = [](const std::string& p) {
    int d = 0;
    for (size_t i = 0; i < p.size(); ++i) d += p[i] == '.' || (p[i] == '[' && i > 0);
    return d;
  };
  if (filter_.empty()) return depth(path);
  if (path == filter_) return 0;
  // inside the selected struct: indented below it
  if (path.rfind(filter_, 0) == 0 && (path[filter_.size()] == '.' || path[filter_.size()] == '[')) {
    return depth(path) - depth(filter_) - 1;
  }
  return -1;
}

void FieldWriter::begin(std::string_view name) {
  const std::string path = path_of(name);
  const int level = level_of(path);
  if (level >= 0 && !filter_.empty() && path == filter_) matched_ = true;
  if (level >= 0 && path != filter_) text_ += std::string(2 * level, ' ') + std::string(name) + ":\n";
  path_.emplace_back(name);
  item_pending_.push_back(false);
}

void FieldWriter::begin_item(size_t index) {
  begin(fmt::format("[{}]", index));
  // the item's own "[i]:" line is not YAML: its first field gets the "- " instead
  const std::string path = path_of("");
  if (level_of(path) >= 0 && path != filter_) {
    text_.resize(text_.size() - (path_.back().size() + 2) - 2 * static_cast<size_t>(level_of(path)));
    item_pending_.back() = true;
  }
}

void FieldWriter::end() {
  path_.pop_back();
  item_pending_.pop_back();
}

void FieldWriter::value(std::string_view name, std::string_view text) {
  const std::string path = path_of(name);
  const int level = level_of(path);
  if (level < 0) return;
  if (path == filter_) {
    matched_ = true;
    text_ += std::string(text) + "\n";
    return;
  }
  std::string indent(2 * static_cast<size_t>(level), ' ');
  if (!item_pending_.empty() && item_pending_.back()) {
    // "- " in place of the item's first field's last two spaces of indent
    indent.replace(indent.size() - 2, 2, "- ");
    item_pending_.back() = false;
  }
  text_ += indent + std::string(name) + ": " + std::string(text) + "\n";
}

void FieldWriter::values(std::string_view name, const std::vector<std::string>& items) {
  std::string text = "[";
  for (const std::string& item : items) text += (text.size() > 1 ? ", " : "") + item;
  value(name, std::string_view(text + "]"));
}

}  // namespace teleop::tools
