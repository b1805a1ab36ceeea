#pragma once
// Replacing a small file so that a reader sees the old or the new content, never a mix.

#include <string>

namespace teleop::bag {

/// Writes `text` to "<path>.tmp", syncs it to disk and renames it over `path`. Throws BagError
/// naming the file ("... disk full ..." on ENOSPC); the old file is left untouched then.
void write_file_atomically(const std::string& path, const std::string& text);

}  // namespace teleop::bag
