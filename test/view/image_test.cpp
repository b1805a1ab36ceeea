#include "teleop/view/image.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>

namespace teleop::view {
namespace {

TEST(Image, APngReadsBackAsWritten) {
  Image image(5, 3);
  for (size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = static_cast<uint8_t>(i * 7);
  const std::string path =
      (std::filesystem::temp_directory_path() / ("teleop-view-image-" + std::to_string(::getpid()) + ".png")).string();
  write_png(image, path);
  const Image back = read_png(path);
  std::filesystem::remove(path);
  EXPECT_EQ(back.width, 5);
  EXPECT_EQ(back.height, 3);
  EXPECT_EQ(back.rgb, image.rgb);
}

TEST(Image, FlippingReversesTheRows) {
  Image image(2, 3);
  for (int y = 0; y < 3; ++y) {
    for (int k = 0; k < 6; ++k) image.rgb[static_cast<size_t>(y * 6 + k)] = static_cast<uint8_t>(y);
  }
  image.flip_rows();
  EXPECT_EQ(image.pixel(0, 0)[0], 2);
  EXPECT_EQ(image.pixel(1, 1)[0], 1);
  EXPECT_EQ(image.pixel(1, 2)[2], 0);
}

TEST(Image, AFileThatIsNoPngIsAnErrorNamingIt) {
  EXPECT_THROW(read_png("/nonexistent/x.png"), ImageError);
  EXPECT_THROW(write_png(Image(1, 1), "/nonexistent/x.png"), ImageError);
}

}  // namespace
}  // namespace teleop::view
