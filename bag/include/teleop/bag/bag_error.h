#pragma once
// The one exception of teleop::bag.

#include <stdexcept>

namespace teleop::bag {

/// A recording that cannot be written or read. The message names the file (the bag's folder,
/// its database or its metadata.yaml) and what is wrong, e.g.
/// "/data/run1/run1_0.db3: disk full while appending a message (...)".
struct BagError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace teleop::bag
