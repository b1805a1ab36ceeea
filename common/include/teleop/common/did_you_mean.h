#pragma once
// "Did you mean": the known name closest to a mistyped one, for config keys and command lines.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace teleop {

/// Edits (insert, delete, substitute, swap two neighbours) that turn `a` into `b`.
size_t edit_distance(std::string_view a, std::string_view b);

/// The candidate nearest to `word`, if it is near enough to be a typo of it: one edit in a word
/// of under 8 letters, two in a longer one, and fewer than half of its letters changed ("jionts"
/// -> "joints", "lauch" -> "launch"; "deploy" suggests no "replay", "x" nothing). Ties go to the
/// first candidate.
std::optional<std::string> closest_name(std::string_view word, const std::vector<std::string>& candidates);

/// " (did you mean 'joints'?)" or "" – to append to an error message.
std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace teleop
