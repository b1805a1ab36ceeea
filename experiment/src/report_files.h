#pragma once
// Where a study leaves its results: a report folder (the one asked for, or a new one in /tmp) and
// whole text files written into it. Shared by the experiment, the soak and the hand study.

#include <string>

namespace teleop::experiment {

/// `requested` (created with its parents) or, when empty, a new folder
/// <temp>/<prefix>XXXXXX. Throws std::runtime_error when it cannot be made.
std::string make_report_dir(const std::string& requested, const std::string& prefix);

/// `v` printed with the printf `spec` ("%.3g"); NaN as "–" (tables).
std::string format_number(const char* spec, double v);

/// `text` as one quoted CSV field (RFC 4180: its quotes doubled), for free text such as an error.
std::string csv_quoted(const std::string& text);

/// Writes `text` to `path`, replacing it. Throws std::runtime_error naming the path on failure.
void write_text(const std::string& path, const std::string& text);

}  // namespace teleop::experiment
