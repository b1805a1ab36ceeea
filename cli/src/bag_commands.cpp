#include "bag_commands.h"

#include "teleop/bag/recording_copy.h"
#include "teleop/tools/bag_tools.h"
#include "teleop/tools/recording_csv.h"

namespace teleop::cli {

BagCommands::BagCommands(CLI::App& app) {
  CLI::App* bag = app.add_subcommand("bag", "recordings (MCAP files, sqlite3 bag folders): info, convert, repair, export");
  bag->require_subcommand(1);
  info_ = bag->add_subcommand("info", "format, compression, duration and each topic's type and count");
  info_->add_option("recording", path_, "an MCAP file or a sqlite3 bag folder")->required();
  convert_ = bag->add_subcommand("convert", "copy a recording into the other format (a .mcap output is MCAP, "
                                            "anything else a sqlite3 bag folder)");
  convert_->add_option("in", path_, "the recording to read")->required();
  convert_->add_option("out", out_, "the recording to write (must not exist)")->required();
  repair_ = bag->add_subcommand("repair", "give an MCAP file that a killed recorder left its summary and indexes");
  repair_->add_option("file", path_, "the MCAP file (rewritten in place)")->required();
  export_ = bag->add_subcommand("export", "write each topic's messages as a CSV file, fields as columns");
  export_->add_option("recording", path_, "an MCAP file or a sqlite3 bag folder")->required();
  export_->add_option("-o,--out", out_, "folder for the CSV files (default: the recording's path + '_csv')");
  export_->add_option("--topics", topics_, "only these topics (default: all)")->delimiter(',');
}

namespace {

int print_export(const tools::CsvExport& result) {
  for (const tools::CsvTopicFile& f : result.files) {
    std::printf("wrote %s: %llu rows", f.path.c_str(), static_cast<unsigned long long>(f.rows));
    if (f.undecodable > 0) std::printf(", %llu messages undecodable", static_cast<unsigned long long>(f.undecodable));
    if (f.values_left_out > 0) {
      std::printf(", %llu values of fields its header lacks left out", static_cast<unsigned long long>(f.values_left_out));
    }
    std::printf("\n");
  }
  for (const std::string& why : result.skipped) std::printf("skipped %s\n", why.c_str());
  return 0;
}

}  // namespace

std::optional<int> BagCommands::run() const {
  if (info_->parsed()) {
    std::printf("%s", tools::bag_info(path_).c_str());
    return 0;
  }
  if (convert_->parsed()) {
    const uint64_t n = tools::convert_recording(path_, out_, tools::format_of_path(out_));
    std::printf("converted %llu messages into %s\n", static_cast<unsigned long long>(n), out_.c_str());
    return 0;
  }
  if (repair_->parsed()) {
    const uint64_t n = bag::repair_mcap(path_);
    std::printf("repaired %s: %llu messages, with summary and indexes\n", path_.c_str(),
                static_cast<unsigned long long>(n));
    return 0;
  }
  if (export_->parsed()) return print_export(tools::export_csv(path_, out_.empty() ? tools::recording_stem(path_) + "_csv" : out_, topics_));
  return std::nullopt;
}

}  // namespace teleop::cli
