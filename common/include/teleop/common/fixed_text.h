#pragma once
// A short text held by value (truncated to fit): records that carry names (a writer's node, a
// topic) copy bytewise between threads and never allocate.

#include <cstddef>
#include <cstring>
#include <string_view>

namespace teleop {

template <size_t N>
struct FixedText {
  char text[N] = {};

  void assign(std::string_view s) {
    const size_t n = s.size() < N - 1 ? s.size() : N - 1;
    // an empty view may hold a null pointer, which memcpy must not get even for 0 bytes
    if (n > 0) std::memcpy(text, s.data(), n);
    text[n] = '\0';
  }
  std::string_view view() const { return {text, strnlen(text, N)}; }
  bool empty() const { return text[0] == '\0'; }
  bool operator==(std::string_view s) const { return view() == s; }
};

}  // namespace teleop
