#include "teleop/common/data_paths.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "teleop/common/config.h"
#include "test_helpers.h"

namespace teleop {
namespace {
namespace fs = std::filesystem;

// A fake install prefix, source tree and configured prefix, each with its own copy of a file.
class DataPaths : public ::testing::Test {
 protected:
  DataPaths() {
    roots_.beside_executable = fs::path(dir_.path("prefix")) / "share" / "teleop";
    roots_.source = dir_.path("src");
    roots_.configured_install = fs::path(dir_.path("usr_local")) / "share" / "teleop";
  }

  // writes <root>/<relative> with the root's name as content
  std::string put(const fs::path& root, const std::string& relative) const {
    const fs::path file = root / relative;
    fs::create_directories(file.parent_path());
    std::ofstream(file) << root.string();
    return file.string();
  }

  test::TempDir dir_{"teleop_data_paths_test"};
  DataRoots roots_;
};

TEST_F(DataPaths, AnInstalledTreeBesideTheExecutableWinsOverTheSourceTree) {
  const std::string installed = put(roots_.beside_executable, "config/scenarios/demo.yaml");
  put(roots_.source, "config/scenarios/demo.yaml");
  put(roots_.configured_install, "config/scenarios/demo.yaml");
  EXPECT_EQ(find_named_config("scenarios", "demo", roots_), installed);
  EXPECT_EQ(resolve_config("scenarios", "demo", roots_), installed);
}

TEST_F(DataPaths, TheSourceTreeComesBeforeTheConfiguredPrefix) {
  const std::string source = put(roots_.source, "config/nodes/follower.yaml");
  put(roots_.configured_install, "config/nodes/follower.yaml");
  EXPECT_EQ(find_named_config("nodes", "follower", roots_), source);
}

TEST_F(DataPaths, TheConfiguredPrefixIsTheLastResort) {
  const std::string last = put(roots_.configured_install, "config/network/wan-35ms.yaml");
  EXPECT_EQ(find_named_config("network", "wan-35ms", roots_), last);
}

TEST_F(DataPaths, ANameMayCarryItsYamlExtension) {
  const std::string file = put(roots_.source, "config/scenarios/demo.yaml");
  EXPECT_EQ(find_named_config("scenarios", "demo.yaml", roots_), file);
}

TEST_F(DataPaths, AKindIsAFolderOfItsOwn) {
  put(roots_.source, "config/nodes/demo.yaml");
  EXPECT_TRUE(find_named_config("scenarios", "demo", roots_).empty());
}

TEST_F(DataPaths, AFolderOfTheSameNameIsNotAConfig) {
  fs::create_directories(roots_.beside_executable / "config/scenarios/demo.yaml");
  const std::string source = put(roots_.source, "config/scenarios/demo.yaml");
  EXPECT_EQ(find_named_config("scenarios", "demo", roots_), source);
}

TEST_F(DataPaths, PathsAreNotNames) {
  put(roots_.source, "config/scenarios/demo.yaml");
  EXPECT_TRUE(find_named_config("scenarios", "x/demo", roots_).empty());
  EXPECT_TRUE(find_named_config("scenarios", "", roots_).empty());
  EXPECT_TRUE(find_named_config("scenarios", "..", roots_).empty());
  // a path that does not exist is left for the loader to name in its error
  EXPECT_EQ(resolve_config("scenarios", "/nonexistent/demo.yaml", roots_), "/nonexistent/demo.yaml");
}

TEST_F(DataPaths, AnExistingFileOrFolderIsTakenAsGiven) {
  put(roots_.source, "config/scenarios/demo.yaml");
  const std::string mine = dir_.write("mine.yaml", "scenario: {}\n");
  EXPECT_EQ(resolve_config("scenarios", mine, roots_), mine);
  EXPECT_EQ(resolve_config("scenarios", dir_.path("src"), roots_), dir_.path("src"));
}

TEST_F(DataPaths, AFolderHereNamedLikeAConfigDoesNotHideIt) {
  // as in the source tree's root, where follower/ is the node's code
  const std::string named = put(roots_.source, "config/nodes/follower.yaml");
  fs::create_directories(dir_.path("here/follower"));
  fs::create_directories(dir_.path("here/twin"));
  const fs::path before = fs::current_path();
  fs::current_path(dir_.path("here"));
  const std::string resolved = resolve_config("nodes", "follower", roots_);
  const std::string folder = resolve_config("nodes", "twin", roots_);
  fs::current_path(before);
  EXPECT_EQ(resolved, named);
  EXPECT_EQ(folder, "twin") << "no config of that name: the folder is left for the loader to refuse";
}

TEST_F(DataPaths, AnUnknownNameSaysWhereItLooked) {
  const std::string message =
      test::error_of<ConfigError>([&] { resolve_config("scenarios", "no_such_scenario", roots_); });
  EXPECT_NE(message.find("no_such_scenario: no such file, nor a name in "), std::string::npos) << message;
  for (const fs::path& root : {roots_.beside_executable, roots_.source, roots_.configured_install}) {
    EXPECT_NE(message.find((root / "config/scenarios").string()), std::string::npos) << message;
  }
}

TEST_F(DataPaths, AMistypedNameIsNamedWithTheNearestOne) {
  put(roots_.beside_executable, "config/nodes/follower.yaml");
  put(roots_.source, "config/nodes/leader.yaml");
  const auto error = [&](const std::string& name) {
    return test::error_of<ConfigError>([&] { resolve_config("nodes", name, roots_); });
  };
  EXPECT_NE(error("folower").find("(did you mean 'follower'?)"), std::string::npos) << error("folower");
  EXPECT_NE(error("laeder.yaml").find("(did you mean 'leader'?)"), std::string::npos) << error("laeder.yaml");
  EXPECT_EQ(error("twin").find("did you mean"), std::string::npos) << error("twin");
}

TEST_F(DataPaths, InstalledAndSourceLayoutsMayDiffer) {
  // the plotting package: share/teleop/teleop_plot installed, scripts/teleop_plot in the source
  const std::string source = put(roots_.source, "scripts/teleop_plot/__main__.py");
  EXPECT_EQ(find_data("teleop_plot/__main__.py", "scripts/teleop_plot/__main__.py", roots_), source);
  const std::string installed = put(roots_.configured_install, "teleop_plot/__main__.py");
  EXPECT_EQ(find_data("teleop_plot/__main__.py", "scripts/teleop_plot/__main__.py",
                      DataRoots{{}, {}, roots_.configured_install}),
            installed);
}

TEST_F(DataPaths, EmptyRootsAreSkipped) {
  EXPECT_EQ(data_candidates("a", "b", DataRoots{}).size(), 0u);
  EXPECT_EQ(data_candidates("a", "b", DataRoots{{}, "/src", {}}), std::vector<fs::path>{"/src/b"});
  EXPECT_TRUE(find_data("a", "b", DataRoots{}).empty());
}

// this test runs from the build tree: nothing is installed beside it, so names resolve to the
// source tree's config/ (as for every executable of a build)
TEST(DataRootsCurrent, ABuildTreeFindsTheSourceTreesConfigs) {
  const DataRoots roots = DataRoots::current();
  EXPECT_EQ(roots.beside_executable.lexically_normal(),
            (fs::path(TELEOP_BIN_DIR) / ".." / "share" / "teleop").lexically_normal());
  EXPECT_EQ(roots.source, fs::path(TELEOP_SOURCE_DIR));
  EXPECT_EQ(roots.configured_install.filename(), "teleop");
  EXPECT_EQ(resolve_config("scenarios", "demo"), std::string(TELEOP_SOURCE_DIR) + "/config/scenarios/demo.yaml");
  EXPECT_EQ(resolve_config("nodes", "follower"), std::string(TELEOP_SOURCE_DIR) + "/config/nodes/follower.yaml");
}

}  // namespace
}  // namespace teleop
