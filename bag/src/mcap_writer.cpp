#include "teleop/bag/mcap_writer.h"

#include <algorithm>
#include <map>
#include <utility>
#include <vector>

#include "mcap_chunk_builder.h"
#include "mcap_output_file.h"
#include "mcap_summary.h"
#include "recording_tally.h"
#include "teleop/common/clock.h"

namespace teleop::bag {

using namespace mcap;

class McapWriter::Impl {
 public:
  explicit Impl(McapWriterOptions options);

  int add_topic(const TopicInfo& topic);
  void write(const MessageToWrite& message);
  void poll();
  void close();
  bool closed() const { return closed_; }

  const BagStats& stats() const { return tally_.stats(); }
  const std::string& path() const { return file_.path(); }

 private:
  uint16_t schema_id_of(const TopicInfo& topic);
  void check_writable(int topic_id) const;
  void write_chunk(bool capped);
  void append(bool capped);

  McapWriterOptions options_;
  OutputFile file_;
  std::vector<uint8_t> pending_;  // bytes about to be appended to the file
  ChunkBuilder chunk_;
  SummaryBuilder summary_;
  RecordingTally tally_;
  std::vector<std::string> topics_;          // index topic id - 1
  std::vector<uint32_t> sequences_;          // per channel: messages so far
  std::map<std::string, uint16_t> schemas_;  // by name
  int64_t chunk_opened_ns_ = 0;
  bool closed_ = false;
};

McapWriter::Impl::Impl(McapWriterOptions options)
    : options_(std::move(options)), file_(options_.path, options_.max_bytes) {
  RecordEncoder encoder(pending_);
  encoder.raw(kMagic.data(), kMagic.size());
  encode_header(encoder);
  append(false);
}

void McapWriter::Impl::append(bool capped) {
  // what fails to go out is not retried: a record half in the file and again after it would be worse
  std::vector<uint8_t> bytes = std::exchange(pending_, {});
  file_.append({bytes.data(), bytes.size()}, capped);
}

uint16_t McapWriter::Impl::schema_id_of(const TopicInfo& topic) {
  const auto known = schemas_.find(topic.type);
  if (known != schemas_.end()) return known->second;
  SchemaRecord schema;
  schema.id = static_cast<uint16_t>(schemas_.size() + 1);
  schema.name = topic.type;
  // a type without a definition keeps its name: encoding "" says there is nothing to decode with
  schema.encoding = topic.schema.empty() ? "" : (topic.schema_encoding.empty() ? kSchemaEncoding : topic.schema_encoding);
  schema.data = topic.schema;
  RecordEncoder encoder(pending_);
  encode(encoder, schema);
  summary_.add_schema(schema);
  schemas_[schema.name] = schema.id;
  return schema.id;
}

int McapWriter::Impl::add_topic(const TopicInfo& topic) {
  if (closed_) throw BagError(path() + ": the MCAP writer is closed");
  const auto known = std::find(topics_.begin(), topics_.end(), topic.name);
  if (known != topics_.end()) return static_cast<int>(known - topics_.begin()) + 1;
  if (topics_.size() >= 0xFFFF) throw BagError(path() + ": more than 65535 topics");
  ChannelRecord channel;
  channel.id = static_cast<uint16_t>(topics_.size() + 1);
  channel.schema_id = schema_id_of(topic);
  channel.topic = topic.name;
  channel.message_encoding = kMessageEncoding;
  if (!topic.qos_profile.empty()) channel.metadata[kQosMetadataKey] = topic.qos_profile;
  RecordEncoder encoder(pending_);
  encode(encoder, channel);
  // outside any chunk and at once: a streaming reader of a killed recording knows every channel
  append(false);
  summary_.add_channel(channel);
  topics_.push_back(topic.name);
  sequences_.push_back(0);
  tally_.add_topic();
  return channel.id;
}

void McapWriter::Impl::check_writable(int topic_id) const {
  if (closed_) throw BagError(path() + ": the MCAP writer is closed");
  if (topic_id < 1 || topic_id > static_cast<int>(topics_.size())) {
    throw BagError(path() + ": a message of topic id " + std::to_string(topic_id) +
                   ", which was never added (add_topic first)");
  }
}

void McapWriter::Impl::write(const MessageToWrite& m) {
  check_writable(m.topic_id);
  const auto channel = static_cast<uint16_t>(m.topic_id);
  MessageRecord record;
  record.channel_id = channel;
  record.sequence = sequences_[channel - 1]++;
  record.log_time = static_cast<uint64_t>(m.recv_ns);
  record.publish_time = static_cast<uint64_t>(m.publish_ns != 0 ? m.publish_ns : m.recv_ns);
  record.data = {m.data, m.size};
  if (chunk_.empty()) chunk_opened_ns_ = monotonic_now_ns();
  chunk_.add(record);
  tally_.add(m.topic_id, m.recv_ns, m.size);
  if (chunk_.uncompressed_bytes() >= options_.chunk_bytes) write_chunk(true);
  poll();
}

void McapWriter::Impl::poll() {
  if (closed_ || chunk_.empty()) return;
  if (monotonic_now_ns() - chunk_opened_ns_ >= options_.chunk_period_ns) write_chunk(true);
}

// the chunk and its message indexes in one write; the summary learns of it only once it is out
void McapWriter::Impl::write_chunk(bool capped) {
  const auto compression = static_cast<Compression>(options_.compression);
  const FinishedChunk finished = chunk_.finish(compression, file_.offset() + pending_.size(), pending_);
  try {
    append(capped);
  } catch (const BagError&) {
    tally_.roll_back();  // its messages are not in the file
    throw;
  }
  summary_.add_chunk(finished);
  tally_.commit();
}

void McapWriter::Impl::close() {
  if (closed_) return;
  closed_ = true;
  if (!chunk_.empty()) write_chunk(false);
  RecordEncoder encoder(pending_);
  const uint32_t data_crc = file_.crc();  // magic, header and every record before DataEnd
  encode_data_end(encoder, data_crc);
  summary_.finish(file_.offset() + pending_.size(), pending_);
  append(false);
  file_.close();
}

McapWriter::McapWriter(McapWriterOptions options) : impl_(std::make_unique<Impl>(std::move(options))) {}

McapWriter::~McapWriter() {
  try {
    impl_->close();
  } catch (...) {
    // a destructor never throws: every chunk written before stays readable
  }
}

int McapWriter::add_topic(const TopicInfo& topic) { return impl_->add_topic(topic); }
void McapWriter::write(const MessageToWrite& message) { impl_->write(message); }
void McapWriter::poll() { impl_->poll(); }
void McapWriter::close() { impl_->close(); }
const BagStats& McapWriter::stats() const { return impl_->stats(); }
const std::string& McapWriter::data_path() const { return impl_->path(); }

}  // namespace teleop::bag
