#pragma once
// A file mapped read-only into memory, for a reader that jumps around in it (an MCAP summary
// pointing at chunks) without copying it.

#include <string>

#include "record_decoder.h"

namespace teleop::bag::mcap {

class MappedFile {
 public:
  /// Maps `path` whole; throws BagError naming it when it cannot be opened or mapped.
  explicit MappedFile(std::string path);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  ByteSpan bytes() const { return {data_, size_}; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  const uint8_t* data_ = nullptr;
  size_t size_ = 0;
};

}  // namespace teleop::bag::mcap
