#pragma once
// A GLFW window with a current OpenGL context: the on-screen view, or a hidden one whose context
// renders offscreen (`teleop render`). Without a display it fails with a DisplayError saying so,
// never a crash. One window per process; its thread is the one that draws.

#include <mujoco/mujoco.h>

#include <stdexcept>
#include <string>

struct GLFWwindow;

namespace teleop::view {

/// No display to open a window on (no X server, DISPLAY unset or refused), or no OpenGL there.
class DisplayError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class GlWindow {
 public:
  /// Opens the window (`visible` false: hidden, for offscreen rendering) and makes its context
  /// current. Throws DisplayError with GLFW's reason and what to do instead.
  GlWindow(const std::string& title, int width, int height, bool visible);
  ~GlWindow();
  GlWindow(const GlWindow&) = delete;
  GlWindow& operator=(const GlWindow&) = delete;

  GLFWwindow* handle() { return window_; }
  /// The framebuffer's size in pixels (may differ from the window's on a scaled display).
  mjrRect framebuffer() const;
  /// The window's size in screen coordinates (what mouse positions are in).
  void window_size(int& width, int& height) const;
  bool close_requested() const;
  void request_close();
  /// Shows the frame drawn into the back buffer.
  void swap_buffers();
  /// Handles pending input (the callbacks run in here).
  void poll_events();

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace teleop::view
