#pragma once
// Frames into an MP4 (H.264, yuv420p: what browsers and players take) through Debian's ffmpeg,
// fed raw RGB on a pipe. ffmpeg is a separate process: a missing one is an error naming the
// package, its own failure carries its message.

#include <string>

#include "teleop/view/image.h"

namespace teleop::view {

class VideoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class VideoWriter {
 public:
  /// Starts ffmpeg writing `path` (overwritten) at `fps` frames per second of `width` x `height`
  /// (both even). Throws VideoError when ffmpeg cannot be started.
  VideoWriter(const std::string& path, int width, int height, double fps);
  /// Ends ffmpeg if finish() was not called (the file is then incomplete).
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  /// Throws VideoError with ffmpeg's message when it stopped taking frames.
  void write(const Image& frame);
  /// Closes the stream and waits for ffmpeg; throws VideoError with its message when it failed.
  void finish();

 private:
  [[noreturn]] void fail(const std::string& what);

  std::string path_;
  int width_;
  int height_;
  int pipe_fd_ = -1;
  int pid_ = -1;
  std::string log_path_;
};

}  // namespace teleop::view
