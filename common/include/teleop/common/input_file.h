#pragma once
// Reading the files a program takes its input from (configurations, network profiles, scenarios,
// a recording's metadata) without ever blocking on one: a FIFO given as a file would wait for a
// writer forever, a device might never end. Configuration time only: allocates and throws.

#include <string>

namespace teleop {

/// The whole text of the regular file `path`. Anything else is refused before a byte is read
/// (opened non-blocking, then checked with fstat): a folder, a FIFO, a device, a socket. Throws
/// ConfigError naming the path: "<path>: cannot open the file", "<path>: is a folder, not a
/// configuration file", "<path>: is a FIFO (named pipe), not a regular file: ...".
std::string read_input_file(const std::string& path);

}  // namespace teleop
