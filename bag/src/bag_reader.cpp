#include "teleop/bag/bag_reader.h"

#include "recording_source.h"

namespace teleop::bag {

class BagReader::Impl {
 public:
  explicit Impl(const std::string& path) : source_(open_recording(path)) {}

  RecordingSource& source() { return *source_; }
  const RecordingSource& source() const { return *source_; }

  const TopicInfo& topic(int topic_id) const {
    check_topic(topic_id);
    return source_->topics()[static_cast<size_t>(topic_id - 1)];
  }

  int topic_id(const std::string& name) const {
    const auto& topics = source_->topics();
    for (size_t i = 0; i < topics.size(); ++i) {
      if (topics[i].name == name) return static_cast<int>(i) + 1;
    }
    return -1;
  }

  void select(const std::vector<int>& topic_ids) {
    for (int id : topic_ids) check_topic(id);
    source_->select(topic_ids);
    selected_ = true;
  }

  bool next(BagMessage& out) {
    if (!selected_) select({});
    return source_->next(out);
  }

 private:
  void check_topic(int topic_id) const {
    if (topic_id < 1 || topic_id > static_cast<int>(source_->topics().size())) {
      throw BagError(source_->data_path() + ": no topic with id " + std::to_string(topic_id));
    }
  }

  std::unique_ptr<RecordingSource> source_;
  bool selected_ = false;
};

BagReader::BagReader(const std::string& path) : impl_(std::make_unique<Impl>(path)) {}
BagReader::~BagReader() = default;

const std::vector<TopicInfo>& BagReader::topics() const { return impl_->source().topics(); }
const TopicInfo& BagReader::topic(int topic_id) const { return impl_->topic(topic_id); }
int BagReader::topic_id(const std::string& name) const { return impl_->topic_id(name); }
uint64_t BagReader::message_count() const { return impl_->source().message_count(); }
int64_t BagReader::start_ns() const { return impl_->source().start_ns(); }
int64_t BagReader::end_ns() const { return impl_->source().end_ns(); }
void BagReader::select(const std::vector<int>& topic_ids) { impl_->select(topic_ids); }
bool BagReader::next(BagMessage& out) { return impl_->next(out); }
const std::string& BagReader::warning() const { return impl_->source().warning(); }
const std::string& BagReader::db_path() const { return impl_->source().data_path(); }
std::string BagReader::format() const { return impl_->source().format(); }

}  // namespace teleop::bag
