#pragma once
// An RGB picture (8 bits a channel, the top row first) and its PNG file.

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace teleop::view {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgb;  ///< width * height * 3, row after row from the top

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgb(static_cast<size_t>(w) * static_cast<size_t>(h) * 3, 0) {}
  const uint8_t* pixel(int x, int y) const {
    return &rgb[(static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 3];
  }
  /// Reverses the row order (OpenGL reads the bottom row first).
  void flip_rows();
};

/// An image file that cannot be written or read; the message names the file.
class ImageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

void write_png(const Image& image, const std::string& path);
/// Reads an 8-bit RGB or RGBA PNG (alpha dropped).
Image read_png(const std::string& path);

}  // namespace teleop::view
