#include "teleop/view/gl_window.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdlib>

namespace teleop::view {
namespace {

// GLFW reports its reasons through a callback; the last one names why init or a window failed
std::string& last_glfw_error() {
  static std::string text;
  return text;
}

void on_glfw_error(int /*code*/, const char* description) {
  last_glfw_error() = description != nullptr ? description : "";
}

std::string display_hint() {
  const char* display = std::getenv("DISPLAY");
  const std::string where =
      display != nullptr && *display != '\0' ? std::string("DISPLAY=") + display : "DISPLAY is not set";
  return where +
         "; on a machine without a screen run it under a virtual one (`xvfb-run -a teleop ...`), or from "
         "another host with `ssh -X` (docs/view.md)";
}

// GLFW once per process, ended at exit: its connection to the X server stays open between
// windows (an Xvfb without -noreset resets when its last client goes, and refuses the next one
// for a moment: `teleop experiment --render` renders one run after the other)
struct Glfw {
  bool ok = false;
  std::string error;
  Glfw() {
    glfwSetErrorCallback(on_glfw_error);
    ok = glfwInit() == GLFW_TRUE;
    error = last_glfw_error();
  }
  ~Glfw() {
    if (ok) glfwTerminate();
  }
};

const Glfw& glfw() {
  static const Glfw instance;
  return instance;
}

}  // namespace

GlWindow::GlWindow(const std::string& title, int width, int height, bool visible) {
  if (!glfw().ok) {
    throw DisplayError("no display to open a window on (" + glfw().error + "): " + display_hint());
  }
  last_glfw_error().clear();
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
  // MuJoCo's renderer is OpenGL 1.5 + framebuffer objects: any context that gives a compatibility
  // profile will do; no multisampling of the window (software OpenGL pays for every sample)
  glfwWindowHint(GLFW_SAMPLES, 0);
  glfwWindowHint(GLFW_DOUBLEBUFFER, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (window_ == nullptr) {
    const std::string reason = last_glfw_error();
    throw DisplayError("cannot open an OpenGL window (" + reason + "): " + display_hint());
  }
  glfwMakeContextCurrent(window_);
  // no vertical sync: the viewer paces itself (a virtual display has no refresh to wait for)
  glfwSwapInterval(0);
}

GlWindow::~GlWindow() { glfwDestroyWindow(window_); }

mjrRect GlWindow::framebuffer() const {
  mjrRect r{0, 0, 0, 0};
  glfwGetFramebufferSize(window_, &r.width, &r.height);
  return r;
}

void GlWindow::window_size(int& width, int& height) const { glfwGetWindowSize(window_, &width, &height); }

bool GlWindow::close_requested() const { return glfwWindowShouldClose(window_) != 0; }

void GlWindow::request_close() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }

void GlWindow::swap_buffers() { glfwSwapBuffers(window_); }

void GlWindow::poll_events() { glfwPollEvents(); }

}  // namespace teleop::view
