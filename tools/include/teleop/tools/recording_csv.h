#pragma once
// `teleop bag export`: a recording's messages as CSV, one file per topic, each message's fields
// flat in columns (docs/tools.md): what a spreadsheet, pandas or `teleop plot` reads.

#include <cstdint>
#include <string>
#include <vector>

namespace teleop::tools {

/// One topic's CSV file as exported.
struct CsvTopicFile {
  std::string topic;
  std::string path;
  uint64_t rows = 0;
  /// Messages whose bytes held no sample of the topic's type (named in no row, counted here).
  uint64_t undecodable = 0;
  /// Values of fields the file's header lacks (a sequence longer than in the topic's first
  /// message), left out and counted.
  uint64_t values_left_out = 0;
};

struct CsvExport {
  std::vector<CsvTopicFile> files;
  /// Topics not exported: not a teleop type (no decoder), with the reason.
  std::vector<std::string> skipped;
};

/// The file a topic's rows go to: its name with '/' as '.', then ".csv"
/// ("teleop/follower/joint_state" -> "teleop.follower.joint_state.csv").
std::string csv_file_name(const std::string& topic);

/// Writes each topic of the recording at `recording` (an MCAP file or a sqlite3 bag folder) of
/// `topics` (empty: every topic) as `out_dir`/csv_file_name(topic), out_dir created. Columns:
/// t_s (receive time since the recording's first message), recv_ns, publish_ns (0: unknown),
/// then the fields of the topic's first message by their dotted paths, sequences item by item
/// ("q_rad[0]"); a later message without a field leaves its cell empty. Throws bag::BagError for
/// a recording that cannot be read, std::runtime_error for a topic the recording lacks (naming
/// the ones it has) or a file that cannot be written.
CsvExport export_csv(const std::string& recording, const std::string& out_dir, const std::vector<std::string>& topics);

}  // namespace teleop::tools
