#include "teleop/runtime/command_line_hint.h"

#include <gtest/gtest.h>

namespace teleop::runtime {
namespace {

// a command line shaped like `teleop`'s: subcommands with positionals and valued options
class CommandLineHints : public ::testing::Test {
 protected:
  CommandLineHints() : app_("test", "teleop") {
    app_.add_flag("--verbose", verbose_, "");
    CLI::App* launch = app_.add_subcommand("launch", "");
    launch->add_option("scenario", scenario_, "");
    launch->add_option("--duration", duration_, "");
    launch->add_option("--domain", domain_, "");
    CLI::App* topic = app_.add_subcommand("topic", "");
    topic->add_subcommand("echo", "")->add_option("--once", verbose_, "");
    app_.add_subcommand("record", "");
  }
  std::vector<std::string> hints(std::vector<std::string> args) { return command_line_hints(app_, args); }

  CLI::App app_;
  bool verbose_ = false;
  std::string scenario_;
  double duration_ = 0;
  int domain_ = 0;
};

TEST_F(CommandLineHints, NamesTheSubcommandAMistypedOneIsCloseTo) {
  EXPECT_EQ(hints({"lauch", "demo.yaml"}),
            std::vector<std::string>{"'lauch' is not a command of teleop (did you mean 'launch'?)"});
  EXPECT_EQ(hints({"topic", "ehco"}),
            std::vector<std::string>{"'ehco' is not a command of teleop topic (did you mean 'echo'?)"});
}

TEST_F(CommandLineHints, NamesTheFlagAMistypedOneIsCloseToInItsSubcommand) {
  EXPECT_EQ(hints({"launch", "demo.yaml", "--duraton", "5"}),
            std::vector<std::string>{"'--duraton' is not an option of teleop launch (did you mean '--duration'?)"});
  EXPECT_EQ(hints({"launch", "--domian=3"}),
            std::vector<std::string>{"'--domian' is not an option of teleop launch (did you mean '--domain'?)"});
}

TEST_F(CommandLineHints, SaysNothingOfACorrectLineOrOfNamesCloseToNothing) {
  EXPECT_TRUE(hints({"launch", "demo.yaml", "--duration", "5", "--domain", "3"}).empty());
  // an option's value is not a subcommand, even when it looks like one
  EXPECT_TRUE(hints({"launch", "--duration", "lauch"}).empty());
  EXPECT_TRUE(hints({"deploy"}).empty());
  EXPECT_TRUE(hints({"launch", "--colour"}).empty());
}

}  // namespace
}  // namespace teleop::runtime
