#include "teleop/view/image.h"

#include <png.h>

#include <algorithm>
#include <cstdio>
#include <memory>

namespace teleop::view {

void Image::flip_rows() {
  const size_t row = static_cast<size_t>(width) * 3;
  for (int y = 0; y < height / 2; ++y) {
    std::swap_ranges(rgb.begin() + static_cast<std::ptrdiff_t>(static_cast<size_t>(y) * row),
                     rgb.begin() + static_cast<std::ptrdiff_t>(static_cast<size_t>(y + 1) * row),
                     rgb.begin() + static_cast<std::ptrdiff_t>(static_cast<size_t>(height - 1 - y) * row));
  }
}

namespace {

struct FileCloser {
  void operator()(FILE* f) const { std::fclose(f); }
};

}  // namespace

// libpng reports errors through longjmp: each libpng sequence runs in a function of its own with
// setjmp at its start and nothing with a destructor or a modified local after it
namespace {

bool encode(png_structp png, png_infop info, FILE* file, const Image& image) {
  if (setjmp(png_jmpbuf(png)) != 0) return false;
  png_init_io(png, file);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y) png_write_row(png, const_cast<png_bytep>(image.pixel(0, y)));
  png_write_end(png, nullptr);
  return true;
}

bool read_header(png_structp png, png_infop info, FILE* file, png_uint_32* width, png_uint_32* height,
                 size_t* row_bytes) {
  if (setjmp(png_jmpbuf(png)) != 0) return false;
  png_init_io(png, file);
  png_read_info(png, info);
  png_set_expand(png);
  png_set_strip_16(png);
  png_set_strip_alpha(png);
  png_set_gray_to_rgb(png);
  png_read_update_info(png, info);
  *width = png_get_image_width(png, info);
  *height = png_get_image_height(png, info);
  *row_bytes = png_get_rowbytes(png, info);
  return true;
}

bool read_rows(png_structp png, png_byte* row, Image* image) {
  if (setjmp(png_jmpbuf(png)) != 0) return false;
  const size_t width = static_cast<size_t>(image->width);
  for (int y = 0; y < image->height; ++y) {
    png_read_row(png, row, nullptr);
    std::copy_n(row, width * 3, image->rgb.begin() + static_cast<std::ptrdiff_t>(static_cast<size_t>(y) * width * 3));
  }
  return true;
}

}  // namespace

void write_png(const Image& image, const std::string& path) {
  std::unique_ptr<FILE, FileCloser> file(std::fopen(path.c_str(), "wb"));
  if (!file) throw ImageError("cannot write " + path);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png != nullptr ? png_create_info_struct(png) : nullptr;
  const bool ok = info != nullptr && encode(png, info, file.get(), image);
  png_destroy_write_struct(&png, &info);
  if (!ok || std::fflush(file.get()) != 0) throw ImageError("cannot write " + path);
}

Image read_png(const std::string& path) {
  std::unique_ptr<FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) throw ImageError("cannot read " + path);
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png != nullptr ? png_create_info_struct(png) : nullptr;
  png_uint_32 width = 0, height = 0;
  size_t row_bytes = 0;
  Image image;
  bool ok = info != nullptr && read_header(png, info, file.get(), &width, &height, &row_bytes) &&
            row_bytes >= static_cast<size_t>(width) * 3;
  if (ok) {
    image = Image(static_cast<int>(width), static_cast<int>(height));
    std::vector<png_byte> row(row_bytes);
    ok = read_rows(png, row.data(), &image);
  }
  png_destroy_read_struct(&png, &info, nullptr);
  if (!ok) throw ImageError("cannot read " + path + ": not an 8-bit PNG");
  return image;
}

}  // namespace teleop::view
