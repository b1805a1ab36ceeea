#pragma once
// One named counter of a node's report, for process-level tests.

#include <gtest/gtest.h>

#include <string>

#include "teleop/runtime/node_report.h"

namespace teleop::test {

/// The counter's value; fails the test (and returns -1) when the report has no such counter.
inline double counter(const runtime::NodeReport& report, const std::string& name) {
  for (const auto& [key, value] : report.counters) {
    if (key == name) return value;
  }
  ADD_FAILURE() << "no counter " << name;
  return -1;
}

}  // namespace teleop::test
