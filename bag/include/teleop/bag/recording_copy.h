#pragma once
// Copying a recording into another (`teleop bag convert`: sqlite3 <-> MCAP) and rewriting an MCAP
// file that lacks its summary (`teleop bag repair`: a recorder killed with SIGKILL).

#include <cstdint>
#include <functional>
#include <string>

#include "teleop/bag/bag_reader.h"
#include "teleop/bag/mcap_writer.h"
#include "teleop/bag/recording_writer.h"

namespace teleop::bag {

/// What a topic becomes in the copy (its type renamed, its schema filled in); identity when empty.
using TopicMapping = std::function<TopicInfo(const TopicInfo&)>;

/// Adds every topic of `reader` (through `mapping`) to `writer`, then copies every message in
/// receive-time order, and closes the writer. Returns the messages copied.
uint64_t copy_recording(BagReader& reader, RecordingWriter& writer, const TopicMapping& mapping = {});

/// Rewrites the MCAP file `path` with a summary and indexes: everything a streaming reader reads
/// of it (up to its last complete chunk) into "<path>.repair", synced, then renamed over `path`.
/// Returns the messages kept. Throws BagError naming the file (left untouched then).
uint64_t repair_mcap(const std::string& path, McapCompression compression = McapCompression::kZstd);

}  // namespace teleop::bag
