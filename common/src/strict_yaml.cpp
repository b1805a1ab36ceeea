#include "teleop/common/strict_yaml.h"

#include <yaml-cpp/eventhandler.h>

#include <algorithm>
#include <map>
#include <optional>
#include <sstream>
#include <vector>

#include "teleop/common/config.h"

namespace teleop {
namespace {

enum class Kind { kScalar, kNull, kSequence, kMapping };

// a finished node, as its parent and every alias of it see it
struct Shape {
  Kind kind = Kind::kScalar;
  uint64_t size = 1;   // nodes in it, its aliases expanded (a mapping counts its keys)
  int height = 0;      // levels below it: 0 for a scalar or an empty collection
  std::string scalar;  // a scalar's value: an alias of it may be a key
};

// an anchored node; open while its own events run (an alias of it inside would be a cycle)
struct Anchor {
  std::string name;
  bool closed = false;
  Shape shape;
};

// a sequence or mapping whose events are running
struct Collection {
  Collection(bool is_mapping_, std::string path_, const YAML::Mark& mark_, YAML::anchor_t anchor_)
      : is_mapping(is_mapping_), path(std::move(path_)), mark(mark_), anchor(anchor_) {}

  bool is_mapping;
  std::string path;
  YAML::Mark mark;
  YAML::anchor_t anchor;
  uint64_t size = 1;
  int height = 0;
  uint64_t items = 0;                    // a sequence's next index
  bool at_key = true;                    // a mapping's next node is a key
  std::string key;                       // the key of a mapping's next value
  std::map<std::string, int> key_lines;  // the line of each key given so far
};

std::string describe(const Shape& shape) {
  switch (shape.kind) {
    case Kind::kScalar:
      return "'" + shape.scalar + "'";
    case Kind::kSequence:
      return "a list";
    case Kind::kMapping:
      return "a mapping";
    case Kind::kNull:
      break;
  }
  return "nothing";
}

// the checks, event by event: each node is seen once, an alias costs what its anchor's shape
// says (computed once, when the anchored node ended), so the pass is linear in the text
class DocumentCheck final : public YAML::EventHandler {
 public:
  DocumentCheck(std::string source, std::string root_path)
      : source_(std::move(source)), root_path_(std::move(root_path)) {}

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnAnchor(const YAML::Mark&, const std::string& name) override { anchor_name_ = name; }
  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    checked([&] { leaf(mark, anchor, Shape{Kind::kNull, 1, 0, {}}); });
  }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor, const std::string& value) override {
    checked([&] { leaf(mark, anchor, Shape{Kind::kScalar, 1, 0, value}); });
  }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    checked([&] { alias(mark, anchor); });
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    checked([&] { open(mark, anchor, false); });
  }
  void OnSequenceEnd() override {
    checked([&] { close(); });
  }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    checked([&] { open(mark, anchor, true); });
  }
  void OnMapEnd() override {
    checked([&] { close(); });
  }

  /// The first rule the document broke, once the parser has read it all.
  void throw_first_problem() const {
    if (problem_) throw *problem_;
  }

 private:
  // the first problem is kept, not thrown, and the rest of the events ignored: malformed YAML
  // further on is the parser's to report first (it may have started a "key" that was never one)
  template <typename Step>
  void checked(Step&& step) {
    if (problem_) return;
    try {
      step();
    } catch (const ConfigError& e) {
      problem_ = e;
    }
  }
  bool at_key() const { return !stack_.empty() && stack_.back().is_mapping && stack_.back().at_key; }
  // the dotted path of the value that comes next
  std::string value_path() const;
  // where a problem with the next node is: its mapping when it is a key, else its own path
  std::string problem_path() const;
  ConfigError error(const YAML::Mark& mark, const std::string& path, const std::string& problem) const;

  void check_depth(const YAML::Mark& mark, int height) const;
  void start_anchor(YAML::anchor_t anchor);
  void end_anchor(YAML::anchor_t anchor, const Shape& shape);
  void leaf(const YAML::Mark& mark, YAML::anchor_t anchor, const Shape& shape);
  void alias(const YAML::Mark& mark, YAML::anchor_t anchor);
  void open(const YAML::Mark& mark, YAML::anchor_t anchor, bool is_mapping);
  void close();
  void place(const YAML::Mark& mark, const Shape& shape);
  void take_key(const YAML::Mark& mark, const Shape& shape);

  std::string source_;
  std::string root_path_;
  std::vector<Collection> stack_;
  std::vector<Anchor> anchors_;  // by the parser's anchor number (1, 2, ...)
  std::string anchor_name_;      // the name of the anchor the next node starts
  uint64_t aliased_nodes_ = 0;
  std::optional<ConfigError> problem_;
};

std::string DocumentCheck::value_path() const {
  if (stack_.empty()) return root_path_;
  const Collection& parent = stack_.back();
  if (!parent.is_mapping) return parent.path + "[" + std::to_string(parent.items) + "]";
  return parent.path.empty() ? parent.key : parent.path + "." + parent.key;
}

std::string DocumentCheck::problem_path() const {
  if (!at_key()) return value_path();
  return stack_.back().path.empty() ? "(top level)" : stack_.back().path;
}

ConfigError DocumentCheck::error(const YAML::Mark& mark, const std::string& path, const std::string& problem) const {
  const std::string where = mark.line >= 0 ? source_ + ":" + std::to_string(mark.line + 1) : source_;
  return ConfigError(where + ": " + path + ": " + problem);
}

// a value `height` levels high starting at the next slot: its deepest node must stay within bounds
void DocumentCheck::check_depth(const YAML::Mark& mark, int height) const {
  if (static_cast<int>(stack_.size()) + height > kMaxYamlDepth) {
    throw error(mark, value_path(), "nested more than " + std::to_string(kMaxYamlDepth) + " levels deep");
  }
}

void DocumentCheck::start_anchor(YAML::anchor_t anchor) {
  if (anchor == YAML::NullAnchor) return;
  if (anchors_.size() <= anchor) anchors_.resize(anchor + 1);
  anchors_[anchor] = Anchor{anchor_name_, false, {}};
  anchor_name_.clear();
}

void DocumentCheck::end_anchor(YAML::anchor_t anchor, const Shape& shape) {
  if (anchor == YAML::NullAnchor) return;
  anchors_[anchor].closed = true;
  anchors_[anchor].shape = shape;
}

void DocumentCheck::leaf(const YAML::Mark& mark, YAML::anchor_t anchor, const Shape& shape) {
  if (!at_key()) check_depth(mark, 0);
  start_anchor(anchor);
  end_anchor(anchor, shape);
  place(mark, shape);
}

void DocumentCheck::alias(const YAML::Mark& mark, YAML::anchor_t anchor) {
  if (anchor >= anchors_.size() || !anchors_[anchor].closed) {
    throw error(mark, problem_path(), "an alias inside the node it names (the document would be endless)");
  }
  const Anchor& named = anchors_[anchor];
  aliased_nodes_ += named.shape.size - 1;
  if (aliased_nodes_ > kMaxAliasedNodes) {
    throw error(mark, problem_path(),
                "aliases add more than " + std::to_string(kMaxAliasedNodes) + " nodes to the document (*" + named.name +
                    " repeats " + std::to_string(named.shape.size) + " here): refused");
  }
  if (!at_key()) check_depth(mark, named.shape.height);
  place(mark, named.shape);
}

void DocumentCheck::open(const YAML::Mark& mark, YAML::anchor_t anchor, bool is_mapping) {
  if (at_key()) {
    throw error(mark, problem_path(),
                std::string("a key must be a plain name, got ") + (is_mapping ? "a mapping" : "a list"));
  }
  check_depth(mark, 0);
  start_anchor(anchor);
  stack_.emplace_back(is_mapping, value_path(), mark, anchor);
}

void DocumentCheck::close() {
  const Collection done = std::move(stack_.back());
  stack_.pop_back();
  const Shape shape{done.is_mapping ? Kind::kMapping : Kind::kSequence, done.size, done.height, {}};
  end_anchor(done.anchor, shape);
  place(done.mark, shape);
}

// a finished node takes the next slot of its parent
void DocumentCheck::place(const YAML::Mark& mark, const Shape& shape) {
  if (stack_.empty()) return;
  if (at_key()) take_key(mark, shape);
  Collection& parent = stack_.back();
  parent.size += shape.size;
  parent.height = std::max(parent.height, shape.height + 1);
  if (parent.is_mapping) {
    parent.at_key = !parent.at_key;
  } else {
    ++parent.items;
  }
}

// yaml-cpp keeps every entry of a mapping, a repeated key too, and lookups find the first: a
// second value would be silently ignored (and never range-checked), so a repeat is an error; so
// is a key that is not a plain scalar (a list or mapping as a key), which no lookup can name
void DocumentCheck::take_key(const YAML::Mark& mark, const Shape& shape) {
  if (shape.kind != Kind::kScalar)
    throw error(mark, problem_path(), "a key must be a plain name, got " + describe(shape));
  Collection& mapping = stack_.back();
  const auto [first, fresh] = mapping.key_lines.emplace(shape.scalar, mark.line + 1);
  const std::string key_path = mapping.path.empty() ? shape.scalar : mapping.path + "." + shape.scalar;
  if (!fresh) {
    throw error(mark, key_path, "duplicate key (first given on line " + std::to_string(first->second) + ")");
  }
  mapping.key = shape.scalar;
}

}  // namespace

YAML::Node parse_strict_yaml(const std::string& text, const std::string& source, const std::string& root_path) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  DocumentCheck check(source, root_path);
  parser.HandleNextDocument(check);
  check.throw_first_problem();
  // only now the tree: its aliases share their anchor's node, so building it is linear too
  return YAML::Load(text);
}

}  // namespace teleop
