// The sweeps' worker pool (experiment/src/sweep_workers.h): every cell's line back in cell order
// whatever worker ran it, one line per cell even when a cell's text has newlines, a cell that
// throws ends only its worker (its cells come back empty, the parent goes on), no workers refused.
#include "sweep_workers.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace teleop::experiment {
namespace {

TEST(SweepWorkers, EveryCellsLineComesBackInCellOrder) {
  const std::vector<std::string> lines = run_in_workers(7, 3, [](size_t i) { return "cell " + std::to_string(i); });
  ASSERT_EQ(lines.size(), 7u);
  for (size_t i = 0; i < lines.size(); ++i) EXPECT_EQ(lines[i], "cell " + std::to_string(i));
}

TEST(SweepWorkers, ANewlineInACellsTextStaysInItsLine) {
  const std::vector<std::string> lines =
      run_in_workers(2, 1, [](size_t i) { return i == 0 ? std::string("error: line one\nline two;3") : "ok"; });
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], "error: line one line two;3");
  EXPECT_EQ(lines[1], "ok");
}

TEST(SweepWorkers, ACellThatThrowsEndsOnlyItsWorker) {
  // worker 1 runs cells 1 and 3 and dies at 1; worker 0 runs 0 and 2
  const std::vector<std::string> lines = run_in_workers(4, 2, [](size_t i) -> std::string {
    if (i == 1) throw std::runtime_error("cell 1 failed");
    return std::to_string(i);
  });
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0], "0");
  EXPECT_EQ(lines[1], "");
  EXPECT_EQ(lines[2], "2");
  EXPECT_EQ(lines[3], "") << "the worker that died ran no more cells";
}

TEST(SweepWorkers, NoWorkersIsAnError) {
  EXPECT_THROW(run_in_workers(3, 0, [](size_t) { return std::string("x"); }), std::invalid_argument);
}

}  // namespace
}  // namespace teleop::experiment
