#pragma once
// The file an MCAP writer appends to: every byte handed to the kernel at once (what a killed
// process wrote stays), a running CRC of all of it (the data section's), a size cap reported as
// a full disk, and errors naming the file.

#include <cstdint>
#include <string>

#include "record_decoder.h"

namespace teleop::bag::mcap {

class OutputFile {
 public:
  /// Creates `path` (an existing file is an error). `max_bytes` 0: no cap.
  OutputFile(std::string path, int64_t max_bytes);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  /// Writes all of `bytes`; throws BagError "... disk full ..." on ENOSPC or when `capped` and
  /// the cap would be passed (nothing of them is written then). After a write that failed
  /// halfway every append throws: the file ends in a partial record, which readers stop before.
  void append(ByteSpan bytes, bool capped);
  /// Syncs the file to disk and closes it; throws BagError when that fails.
  void close();

  uint64_t offset() const { return offset_; }
  uint32_t crc() const { return crc_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int64_t max_bytes_;
  int fd_ = -1;
  uint64_t offset_ = 0;
  uint32_t crc_ = 0;
  bool torn_ = false;  // a write failed halfway: nothing may follow the partial record
};

}  // namespace teleop::bag::mcap
