#include "teleop/tools/recording_csv.h"

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <stdexcept>
#include <unordered_map>

#include "teleop/bag/bag_reader.h"
#include "teleop/tools/sample_text.h"
#include "teleop/transport/sample_types.h"

namespace teleop::tools {
namespace {

namespace fs = std::filesystem;

// RFC 4180: a field with a comma, quote or line break is quoted, its quotes doubled
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

// One topic's open file: its header from the first message, rows in the header's order.
class TopicCsv {
 public:
  TopicCsv(const transport::SampleType& type, CsvTopicFile& file) : type_(type), file_(file), out_(file.path) {
    if (!out_) throw std::runtime_error("cannot write " + file.path);
  }

  void add(const bag::BagMessage& m, int64_t start_ns) {
    std::vector<std::pair<std::string, std::string>> fields;
    try {
      fields = sample_fields(type_, m.data);
    } catch (const std::runtime_error&) {
      ++file_.undecodable;
      return;
    }
    if (columns_.empty()) write_header(fields);
    std::vector<const std::string*> cells(columns_.size(), nullptr);
    const bool in_header_order = fields.size() == columns_.size() &&
                                 std::equal(fields.begin(), fields.end(), names_.begin(),
                                            [](const auto& f, const std::string& n) { return f.first == n; });
    for (size_t i = 0; i < fields.size(); ++i) {
      if (in_header_order) {
        cells[i] = &fields[i].second;
      } else if (const auto at = columns_.find(fields[i].first); at != columns_.end()) {
        cells[at->second] = &fields[i].second;
      } else {
        ++file_.values_left_out;
      }
    }
    out_ << fmt::format("{:.9f},{},{}", static_cast<double>(m.recv_ns - start_ns) * 1e-9, m.recv_ns, m.publish_ns);
    for (const std::string* cell : cells) out_ << ',' << (cell != nullptr ? csv_field(*cell) : "");
    out_ << '\n';
    ++file_.rows;
  }

  void close() {
    out_.close();
    if (!out_) throw std::runtime_error("cannot write " + file_.path);
  }

 private:
  void write_header(const std::vector<std::pair<std::string, std::string>>& fields) {
    out_ << "t_s,recv_ns,publish_ns";
    for (const auto& [name, value] : fields) {
      columns_.emplace(name, names_.size());
      names_.push_back(name);
      out_ << ',' << csv_field(name);
    }
    out_ << '\n';
  }

  const transport::SampleType& type_;
  CsvTopicFile& file_;
  std::ofstream out_;
  std::vector<std::string> names_;
  std::unordered_map<std::string, size_t> columns_;
};

std::vector<int> selected_topic_ids(const bag::BagReader& reader, const std::vector<std::string>& topics) {
  std::vector<int> ids;
  for (const std::string& topic : topics) {
    const int id = reader.topic_id(topic);
    if (id < 0) {
      std::string have;
      for (const bag::TopicInfo& t : reader.topics()) have += (have.empty() ? "" : ", ") + t.name;
      throw std::runtime_error(fmt::format("{} has no topic '{}' (it has: {})", reader.db_path(), topic, have));
    }
    ids.push_back(id);
  }
  if (ids.empty()) {
    for (size_t i = 0; i < reader.topics().size(); ++i) ids.push_back(static_cast<int>(i) + 1);
  }
  return ids;
}

}  // namespace

std::string csv_file_name(const std::string& topic) {
  std::string name = topic;
  std::replace(name.begin(), name.end(), '/', '.');
  return name + ".csv";
}

CsvExport export_csv(const std::string& recording, const std::string& out_dir, const std::vector<std::string>& topics) {
  bag::BagReader reader(recording);
  const std::vector<int> ids = selected_topic_ids(reader, topics);
  fs::create_directories(out_dir);
  CsvExport result;
  result.files.reserve(ids.size());  // TopicCsv keeps a reference to its file
  std::map<int, std::unique_ptr<TopicCsv>> open;
  for (const int id : ids) {
    const bag::TopicInfo& topic = reader.topic(id);
    const transport::SampleType* type = transport::find_sample_type(topic.type);
    if (type == nullptr) {
      result.skipped.push_back(fmt::format("{}: type '{}' is not a teleop type", topic.name, topic.type));
      continue;
    }
    result.files.push_back({topic.name, (fs::path(out_dir) / csv_file_name(topic.name)).string()});
    open.emplace(id, std::make_unique<TopicCsv>(*type, result.files.back()));
  }
  reader.select(ids);
  bag::BagMessage m;
  while (reader.next(m)) {
    if (const auto at = open.find(m.topic_id); at != open.end()) at->second->add(m, reader.start_ns());
  }
  for (auto& [id, csv] : open) csv->close();
  return result;
}

}  // namespace teleop::tools
