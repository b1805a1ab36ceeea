#pragma once
// What a mistyped command line probably meant: CLI11 says "The following argument was not
// expected: lauch"; this names the subcommand or flag the user most likely wanted.

#include <CLI/App.hpp>

#include <string>
#include <vector>

namespace teleop::runtime {

/// Walks `args` (argv without the program name) through `app`'s subcommands and options the way
/// the parser does and returns one line per unknown subcommand or flag that is close to a known
/// one, e.g. "'lauch' is not a command of teleop (did you mean 'launch'?)". Empty when nothing
/// is close. Call it after a CLI::ParseError, to add to the parser's own message.
std::vector<std::string> command_line_hints(const CLI::App& app, const std::vector<std::string>& args);

/// What a command line's parse error ends in: CLI11's message (or the help, or the version),
/// then the hints above on stderr. Returns the exit code: 0 for --help and --version, else 2.
int exit_after_parse_error(CLI::App& app, const CLI::ParseError& error, int argc, const char* const* argv);

}  // namespace teleop::runtime
