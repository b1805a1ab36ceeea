// An MCAP file as a recording: its channels as topics, its messages in log-time order from the
// catalogue (mcap_catalogue.h), each chunk decompressed when a message in it is read.
#include <algorithm>
#include <memory>

#include "mcap_catalogue.h"
#include "mcap_format.h"
#include "recording_source.h"

namespace teleop::bag {
namespace {

using namespace mcap;

TopicInfo topic_of(const ChannelRecord& channel, const McapCatalogue& catalogue, const std::string& path) {
  TopicInfo topic;
  topic.name = channel.topic;
  if (channel.message_encoding != kMessageEncoding) {
    throw BagError(path + ": topic " + channel.topic + " has message encoding \"" + channel.message_encoding +
                   "\" (teleop reads cdr)");
  }
  const auto qos = channel.metadata.find(kQosMetadataKey);
  if (qos != channel.metadata.end()) topic.qos_profile = qos->second;
  if (channel.schema_id == 0) return topic;
  const auto schema = catalogue.schemas.find(channel.schema_id);
  if (schema == catalogue.schemas.end()) {
    throw BagError(path + ": topic " + channel.topic + " names schema " + std::to_string(channel.schema_id) +
                   ", which the file does not have");
  }
  topic.type = schema->second.name;
  topic.schema = schema->second.data;
  topic.schema_encoding = schema->second.encoding;
  return topic;
}

class McapSource : public RecordingSource {
 public:
  explicit McapSource(const std::string& path) : file_(path), catalogue_(read_catalogue(file_)) {
    for (const auto& [id, channel] : catalogue_.channels) {
      topic_of_channel_[id] = static_cast<int>(topics_.size()) + 1;
      topics_.push_back(topic_of(channel, catalogue_, path));
    }
    for (const MessageRef& m : catalogue_.messages) {
      if (topic_of_channel_.count(m.channel) == 0) {
        throw BagError(path + ": a message of channel " + std::to_string(m.channel) + ", which the file never defines");
      }
      start_ns_ = std::min(start_ns_, m.log_time);
      end_ns_ = std::max(end_ns_, m.log_time);
    }
  }

  const std::vector<TopicInfo>& topics() const override { return topics_; }
  uint64_t message_count() const override { return catalogue_.messages.size(); }
  int64_t start_ns() const override { return catalogue_.messages.empty() ? 0 : static_cast<int64_t>(start_ns_); }
  int64_t end_ns() const override { return static_cast<int64_t>(end_ns_); }
  const std::string& warning() const override { return catalogue_.warning; }
  const std::string& data_path() const override { return file_.path(); }

  std::string format() const override {
    std::string names;
    for (const std::string& c : catalogue_.compressions) names += (names.empty() ? "" : ", ") + (c.empty() ? "none" : c);
    return "mcap (" + (names.empty() ? std::string("no chunks") : names) + (catalogue_.indexed ? ")" : ", streamed)");
  }

  void select(const std::vector<int>& topic_ids) override {
    order_.clear();
    next_ = 0;
    for (uint32_t i = 0; i < catalogue_.messages.size(); ++i) {
      const int topic = topic_of_channel_.at(catalogue_.messages[i].channel);
      if (topic_ids.empty() || std::find(topic_ids.begin(), topic_ids.end(), topic) != topic_ids.end()) {
        order_.push_back(i);
      }
    }
    // by log time, then in file order (as a sqlite3 bag orders by timestamp, then by id)
    std::stable_sort(order_.begin(), order_.end(), [&](uint32_t a, uint32_t b) {
      return catalogue_.messages[a].log_time < catalogue_.messages[b].log_time;
    });
  }

  bool next(BagMessage& out) override {
    if (next_ >= order_.size()) return false;
    const MessageRef& ref = catalogue_.messages[order_[next_++]];
    const MessageRecord m = decode_message(record_of(ref));
    out.topic_id = topic_of_channel_.at(m.channel_id);
    out.recv_ns = static_cast<int64_t>(m.log_time);
    out.publish_ns = static_cast<int64_t>(m.publish_time);
    out.recv_mono_ns = 0;
    out.writer = {};
    out.data.assign(m.data.data, m.data.data + m.data.size);
    return true;
  }

 private:
  // the Message record a reference points at, its chunk decompressed once while it is read
  RecordDecoder record_of(const MessageRef& ref) {
    ByteSpan bytes = file_.bytes();
    if (ref.chunk != MessageRef::kUnchunked) {
      if (ref.chunk != open_chunk_) {
        if (ref.chunk >= catalogue_.chunks.size()) throw BagError(file_.path() + ": a message index names no chunk");
        open_records_ = chunk_records(file_, catalogue_.chunks[ref.chunk], buffer_);
        open_chunk_ = ref.chunk;
      }
      bytes = open_records_;
    }
    const std::string what = file_.path() + ": message at offset " + std::to_string(ref.offset) +
                             (ref.chunk == MessageRef::kUnchunked ? "" : " of chunk " + std::to_string(ref.chunk));
    RecordDecoder in(bytes, what);
    in.take(ref.offset);
    if (static_cast<Op>(in.u8()) != Op::kMessage) throw BagError(what + ": not a Message record");
    return RecordDecoder(in.take(in.u64()), what);
  }

  MappedFile file_;
  McapCatalogue catalogue_;
  std::vector<TopicInfo> topics_;
  std::map<uint16_t, int> topic_of_channel_;
  uint64_t start_ns_ = UINT64_MAX;
  uint64_t end_ns_ = 0;
  std::vector<uint32_t> order_;
  size_t next_ = 0;
  uint32_t open_chunk_ = MessageRef::kUnchunked;
  ByteSpan open_records_;
  std::vector<uint8_t> buffer_;
};

}  // namespace

std::unique_ptr<RecordingSource> open_mcap(const std::string& file) { return std::make_unique<McapSource>(file); }

}  // namespace teleop::bag
