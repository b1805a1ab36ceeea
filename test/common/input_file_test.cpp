#include "teleop/common/input_file.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <future>
#include <string>

#include "teleop/common/config.h"
#include "test_helpers.h"

namespace teleop {
namespace {

using test::TempDir;

std::string error_of(const std::function<void()>& f) { return test::error_of<ConfigError>(f); }

TEST(InputFile, ReadsTheWholeOfARegularFile) {
  TempDir dir("teleop_input_file_test");
  // larger than one read
  const std::string text(200'000, 'x');
  EXPECT_EQ(read_input_file(dir.write("big.yaml", text)), text);
  EXPECT_EQ(read_input_file(dir.write("empty.yaml", "")), "");
}

TEST(InputFile, RefusesAFifoAtOnceInsteadOfWaitingForAWriter) {
  TempDir dir("teleop_input_file_test");
  const std::string fifo = dir.path("config.yaml");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  auto reading = std::async(std::launch::async, [&] { return error_of([&] { read_input_file(fifo); }); });
  if (reading.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
    ADD_FAILURE() << "blocked on the FIFO";
    // a writer releases the blocked open, so that the test can end
    const int fd = ::open(fifo.c_str(), O_WRONLY);
    ::close(fd);
  }
  EXPECT_EQ(reading.get(), fifo +
                               ": is a FIFO (named pipe), not a regular file: refused (reading it could wait or run "
                               "forever)");
}

TEST(InputFile, RefusesADeviceAFolderAndAMissingFileNamingEach) {
  TempDir dir("teleop_input_file_test");
  EXPECT_EQ(error_of([] { read_input_file("/dev/zero"); }),
            "/dev/zero: is a character device, not a regular file: refused (reading it could wait or run forever)");
  EXPECT_EQ(error_of([&] { read_input_file(dir.path("")); }), dir.path("") + ": is a folder, not a configuration file");
  EXPECT_EQ(error_of([&] { read_input_file(dir.path("none.yaml")); }),
            dir.path("none.yaml") + ": cannot open the file");
}

}  // namespace
}  // namespace teleop
