// The allocation counter must see allocations, or the "does not allocate" tests prove nothing.
#include "allocation_counter.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "teleop/common/version.h"

namespace teleop::test {
namespace {

TEST(AllocationCounter, CountsEveryAllocationOfThisThread) {
  ScopedAllocationCounter counter;
  auto one = std::make_unique<int>(1);
  std::vector<double> v;
  v.reserve(100);
  std::string s(100, 'x');
  EXPECT_EQ(counter.count(), 3u);
}

// teleop's libraries are shared (docs/install.md): their calls to operator new must still reach
// the test's replacement, or a real-time function in a library would pass "allocates nothing"
TEST(AllocationCounter, CountsAllocationsInsideTeleopsLibraries) {
  ScopedAllocationCounter counter;
  const std::string text = version_text();  // builds a string longer than the small-string buffer
  EXPECT_GT(text.size(), 15u);
  EXPECT_GE(counter.count(), 1u);
}

TEST(AllocationCounter, IgnoresOtherThreads) {
  ScopedAllocationCounter counter;
  std::unique_ptr<int> other;
  std::thread t([&] { other = std::make_unique<int>(2); });
  const uint64_t before_join = counter.count();  // std::thread itself allocates its state here
  t.join();
  EXPECT_EQ(counter.count(), before_join);
  EXPECT_EQ(*other, 2);
}

TEST(AllocationCounter, CountsNothingForStackWork) {
  ScopedAllocationCounter counter;
  double sum = 0;
  for (int i = 0; i < 1000; ++i) sum += i;
  EXPECT_EQ(sum, 499500.0);
  EXPECT_EQ(counter.count(), 0u);
}

}  // namespace
}  // namespace teleop::test
