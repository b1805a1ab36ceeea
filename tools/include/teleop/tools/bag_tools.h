#pragma once
// `teleop bag info|convert|repair`: a recording summarised, converted between MCAP and rosbag2's
// sqlite3 layout, or an MCAP file a killed recorder left given its summary (docs/tools.md).

#include <cstdint>
#include <string>

#include "teleop/tools/message_schemas.h"

namespace teleop::tools {

/// The recording's format and compression, duration, message count and its topics with type
/// and count, as text. Throws bag::BagError naming the file.
std::string bag_info(const std::string& path);

/// Copies the recording `in` into a new one at `out` of `format` (a folder for sqlite3, a file
/// for MCAP), teleop's types renamed and given their schemas as `format` keeps them. Returns the
/// messages copied.
uint64_t convert_recording(const std::string& in, const std::string& out, RecordingFormat format);

/// Whether `path` is a recording rather than a run's trace folder: a file (MCAP), or a folder
/// with a sqlite3 bag's metadata.yaml or database (one a killed recorder left has no metadata).
bool is_recording(const std::string& path);

/// What a recording's derived outputs are named after: its path without a trailing '/'
/// ("run1/" -> "run1": its CSV export is run1_csv, its figures run1_plots).
std::string recording_stem(std::string path);

/// The format a path names: a ".mcap" file is MCAP, anything else a sqlite3 bag folder.
RecordingFormat format_of_path(const std::string& path);

}  // namespace teleop::tools
