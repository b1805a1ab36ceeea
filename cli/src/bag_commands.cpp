#include "bag_commands.h"

#include "teleop/bag/recording_copy.h"
#include "teleop/tools/bag_tools.h"

namespace teleop::cli {

BagCommands::BagCommands(CLI::App& app) {
  CLI::App* bag = app.add_subcommand("bag", "recordings (MCAP files, sqlite3 bag folders): info, convert, repair");
  bag->require_subcommand(1);
  info_ = bag->add_subcommand("info", "format, compression, duration and each topic's type and count");
  info_->add_option("recording", path_, "an MCAP file or a sqlite3 bag folder")->required();
  convert_ = bag->add_subcommand("convert", "copy a recording into the other format (a .mcap output is MCAP, "
                                            "anything else a sqlite3 bag folder)");
  convert_->add_option("in", path_, "the recording to read")->required();
  convert_->add_option("out", out_, "the recording to write (must not exist)")->required();
  repair_ = bag->add_subcommand("repair", "give an MCAP file that a killed recorder left its summary and indexes");
  repair_->add_option("file", path_, "the MCAP file (rewritten in place)")->required();
}

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
  return std::nullopt;
}

}  // namespace teleop::cli
