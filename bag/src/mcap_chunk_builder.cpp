#include "mcap_chunk_builder.h"

#include <algorithm>

namespace teleop::bag::mcap {

void ChunkBuilder::add(const MessageRecord& message) {
  if (records_.empty()) {
    start_time_ = message.log_time;
    end_time_ = message.log_time;
  }
  start_time_ = std::min(start_time_, message.log_time);
  end_time_ = std::max(end_time_, message.log_time);
  MessageIndexRecord& index = indexes_[message.channel_id];
  index.channel_id = message.channel_id;
  index.entries.emplace_back(message.log_time, records_.size());
  RecordEncoder encoder(records_);
  encode(encoder, message);
}

FinishedChunk ChunkBuilder::finish(Compression compression, uint64_t file_offset, std::vector<uint8_t>& out) {
  const ByteSpan records{records_.data(), records_.size()};
  compress(compression, records, compressed_);
  ChunkRecord chunk;
  chunk.message_start_time = start_time_;
  chunk.message_end_time = end_time_;
  chunk.uncompressed_size = records.size;
  chunk.uncompressed_crc = crc32_of(records);
  chunk.compression = compression_name(compression);
  chunk.records = {compressed_.data(), compressed_.size()};

  FinishedChunk finished;
  ChunkIndexRecord& index = finished.index;
  index.message_start_time = start_time_;
  index.message_end_time = end_time_;
  index.chunk_start_offset = file_offset + out.size();
  index.compression = chunk.compression;
  index.compressed_size = compressed_.size();
  index.uncompressed_size = records.size;
  RecordEncoder encoder(out);
  encode(encoder, chunk);
  index.chunk_length = file_offset + out.size() - index.chunk_start_offset;

  const uint64_t indexes_start = file_offset + out.size();
  for (auto& [channel, message_index] : indexes_) {
    // readers may binary-search an index: by log time, messages of equal time in the order written
    std::stable_sort(message_index.entries.begin(), message_index.entries.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    index.message_index_offsets[channel] = file_offset + out.size();
    finished.message_counts[channel] = message_index.entries.size();
    encode(encoder, message_index);
  }
  index.message_index_length = file_offset + out.size() - indexes_start;
  records_.clear();
  indexes_.clear();
  return finished;
}

}  // namespace teleop::bag::mcap
