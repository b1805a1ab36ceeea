#pragma once
// A "billion laughs" for the tests of every YAML reader: level 0 (`l0`, line 1) is nine scalars,
// each level after it (`l<n>`, line n + 1) nine aliases of the one before, so that `levels` + 1
// short lines mean 9^(levels + 1) scalars to anything that expands the aliases. Parsed strictly
// (strict_yaml.h) the first alias of level 5 crosses the budget: "<file>:6: l5[0]: aliases add
// more than 100000 nodes to the document (*l4 repeats 66430 here): refused".

#include <string>

namespace teleop::test {

inline std::string alias_bomb(int levels) {
  std::string text = "l0: &l0 [lol, lol, lol, lol, lol, lol, lol, lol, lol]\n";
  for (int level = 1; level <= levels; ++level) {
    const std::string before = "*l" + std::to_string(level - 1);
    text += "l" + std::to_string(level) + ": &l" + std::to_string(level) + " [";
    for (int i = 0; i < 9; ++i) text += (i == 0 ? "" : ", ") + before;
    text += "]\n";
  }
  return text;
}

/// What the strict reader says about alias_bomb(levels) for any levels >= 5, after "<file>:6: ".
inline constexpr const char* kAliasBombError =
    "l5[0]: aliases add more than 100000 nodes to the document (*l4 repeats 66430 here): refused";

}  // namespace teleop::test
