// Telling a recording's format from its path: a folder is a sqlite3 bag, a file is read as MCAP
// when it starts with MCAP's magic.
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "mcap_format.h"
#include "recording_source.h"
#include "teleop/bag/bag_error.h"

namespace teleop::bag {
namespace {

bool starts_with_mcap_magic(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) throw BagError(path + ": cannot be opened (" + std::strerror(errno) + ")");
  unsigned char head[mcap::kMagic.size()] = {};
  const size_t n = std::fread(head, 1, sizeof head, f);
  std::fclose(f);
  return n == sizeof head && std::memcmp(head, mcap::kMagic.data(), sizeof head) == 0;
}

}  // namespace

std::unique_ptr<RecordingSource> open_recording(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return open_sqlite_bag(path);
  if (!std::filesystem::exists(path, ec)) throw BagError(path + ": no such file or folder");
  if (!starts_with_mcap_magic(path)) {
    throw BagError(path + ": not a recording (an MCAP file starts with its magic bytes \\x89MCAP0; a sqlite3 "
                          "bag is a folder)");
  }
  return open_mcap(path);
}

}  // namespace teleop::bag
