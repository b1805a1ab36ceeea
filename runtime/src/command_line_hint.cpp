#include "teleop/runtime/command_line_hint.h"

#include "teleop/common/did_you_mean.h"

#include <cstdio>
#include <filesystem>

namespace teleop::runtime {
namespace {

std::vector<const CLI::App*> subcommands_of(const CLI::App& app) {
  return app.get_subcommands([](const CLI::App*) { return true; });
}

const CLI::App* find_subcommand(const CLI::App& app, const std::string& name) {
  for (const CLI::App* sub : subcommands_of(app)) {
    if (sub->check_name(name)) return sub;
  }
  return nullptr;
}

std::vector<std::string> subcommand_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* sub : subcommands_of(app)) names.push_back(sub->get_name());
  return names;
}

std::vector<std::string> long_flags(const CLI::App& app) {
  std::vector<std::string> flags;
  for (const CLI::Option* option : app.get_options()) {
    for (const std::string& name : option->get_lnames()) flags.push_back("--" + name);
  }
  return flags;
}

// the name an app is called by in a message: "teleop" or "teleop launch"
std::string command_name(const CLI::App& app) {
  // the root is named after argv[0] when unnamed: "teleop", not "build/default/bin/teleop"
  const auto base = [](const CLI::App& a) { return std::filesystem::path(a.get_name()).filename().string(); };
  std::string name = base(app);
  for (const CLI::App* parent = app.get_parent(); parent != nullptr; parent = parent->get_parent()) {
    name = base(*parent) + " " + name;
  }
  return name;
}

}  // namespace

std::vector<std::string> command_line_hints(const CLI::App& app, const std::vector<std::string>& args) {
  std::vector<std::string> hints;
  const CLI::App* current = &app;
  for (size_t k = 0; k < args.size(); ++k) {
    const std::string& arg = args[k];
    if (arg == "--") break;  // the rest is positional by definition
    if (arg.rfind("--", 0) == 0) {
      const std::string flag = arg.substr(0, arg.find('='));
      const CLI::Option* option = current->get_option_no_throw(flag);
      if (option == nullptr) {
        const std::string hint = did_you_mean(flag, long_flags(*current));
        if (!hint.empty()) hints.push_back("'" + flag + "' is not an option of " + command_name(*current) + hint);
      } else if (option->get_expected_min() > 0 && flag.size() == arg.size()) {
        ++k;  // its value follows
      }
      continue;
    }
    if (arg.rfind('-', 0) == 0) continue;  // short flags: too short to guess from
    if (subcommands_of(*current).empty()) continue;  // a positional argument
    if (const CLI::App* sub = find_subcommand(*current, arg)) {
      current = sub;
      continue;
    }
    const std::string hint = did_you_mean(arg, subcommand_names(*current));
    if (!hint.empty()) hints.push_back("'" + arg + "' is not a command of " + command_name(*current) + hint);
    break;  // what follows belonged to a command we do not know
  }
  return hints;
}

int exit_after_parse_error(CLI::App& app, const CLI::ParseError& error, int argc, const char* const* argv) {
  if (app.exit(error) == 0) return 0;
  const std::vector<std::string> args(argv + 1, argv + argc);
  for (const std::string& hint : command_line_hints(app, args)) std::fprintf(stderr, "%s\n", hint.c_str());
  return 2;
}

}  // namespace teleop::runtime
