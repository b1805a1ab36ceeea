#include "teleop/view/video_writer.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

extern char** environ;

namespace teleop::view {

namespace {

std::string read_all(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

}  // namespace

VideoWriter::VideoWriter(const std::string& path, int width, int height, double fps)
    : path_(path), width_(width), height_(height) {
  if (width % 2 != 0 || height % 2 != 0) throw VideoError(path + ": an MP4's width and height must be even");
  // a pipe whose reader died must fail a write, not kill this process
  std::signal(SIGPIPE, SIG_IGN);
  char log_template[] = "/tmp/teleop-ffmpeg-XXXXXX";
  const int log_fd = mkstemp(log_template);
  if (log_fd < 0) throw VideoError("cannot make a log file for ffmpeg in /tmp");
  log_path_ = log_template;
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) {
    close(log_fd);
    throw VideoError("cannot make a pipe to ffmpeg");
  }
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  char rate[32];
  std::snprintf(rate, sizeof rate, "%g", fps);
  std::vector<std::string> args = {"ffmpeg",   "-nostdin", "-y",      "-loglevel", "error",      "-f",       "rawvideo",
                                   "-pix_fmt", "rgb24",    "-s",      size,        "-r",         rate,       "-i",
                                   "-",        "-an",      "-c:v",    "libx264",   "-preset",    "veryfast", "-crf",
                                   "26",       "-pix_fmt", "yuv420p", "-movflags", "+faststart", path};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, log_fd, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, log_fd, STDERR_FILENO);
  pid_t pid = -1;
  const int rc = posix_spawnp(&pid, "ffmpeg", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[0]);
  close(log_fd);
  if (rc != 0) {
    close(fds[1]);
    std::remove(log_path_.c_str());
    throw VideoError("cannot start ffmpeg to write " + path + " (" + std::string(std::strerror(rc)) +
                     "; Debian's package: ffmpeg, scripts/setup.sh installs it)");
  }
  pid_ = pid;
  pipe_fd_ = fds[1];
}

VideoWriter::~VideoWriter() {
  if (pipe_fd_ >= 0) close(pipe_fd_);
  if (pid_ > 0) {
    int status = 0;
    waitpid(pid_, &status, 0);
  }
  if (!log_path_.empty()) std::remove(log_path_.c_str());
}

void VideoWriter::fail(const std::string& what) {
  if (pipe_fd_ >= 0) close(pipe_fd_);
  pipe_fd_ = -1;
  int status = 0;
  if (pid_ > 0) waitpid(pid_, &status, 0);
  pid_ = -1;
  const std::string log = read_all(log_path_);
  throw VideoError(path_ + ": " + what + (log.empty() ? "" : ": ffmpeg: " + log));
}

void VideoWriter::write(const Image& frame) {
  if (frame.width != width_ || frame.height != height_) {
    throw VideoError(path_ + ": a frame of " + std::to_string(frame.width) + "x" + std::to_string(frame.height) +
                     " in a video of " + std::to_string(width_) + "x" + std::to_string(height_));
  }
  if (pipe_fd_ < 0) fail("the video is closed");
  const uint8_t* p = frame.rgb.data();
  size_t left = frame.rgb.size();
  while (left > 0) {
    const ssize_t n = ::write(pipe_fd_, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail("ffmpeg stopped taking frames");
    p += n;
    left -= static_cast<size_t>(n);
  }
}

void VideoWriter::finish() {
  close(pipe_fd_);
  pipe_fd_ = -1;
  int status = 0;
  const pid_t pid = pid_;
  pid_ = -1;
  if (waitpid(pid, &status, 0) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const std::string log = read_all(log_path_);
    throw VideoError(path_ + ": ffmpeg failed" + (log.empty() ? "" : ": " + log));
  }
}

}  // namespace teleop::view
