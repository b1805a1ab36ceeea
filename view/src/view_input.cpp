#include "teleop/view/view_input.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace teleop::view {

const char* const kKeyHelp =
    "Esc\tquit\n"
    "Space\tfreeze / go on\n"
    "Right\tone step while frozen\n"
    "C\tcontacts on / off\n"
    "T\ttwin ghost on / off\n"
    "L\tleader ghost on / off\n"
    "S\tside-by-side stereo on / off\n"
    "Backspace\tcamera back to the start\n"
    "F1\tthis help\n"
    "Left drag\trotate (Shift: horizontal)\n"
    "Right drag\tmove (Shift: horizontal)\n"
    "Wheel, middle drag\tzoom";

namespace {

ViewInput* input_of(GLFWwindow* w) { return static_cast<ViewInput*>(glfwGetWindowUserPointer(w)); }

}  // namespace

ViewInput::ViewInput(GlWindow& window, SceneRenderer& renderer, const mjModel* model)
    : window_(&window), renderer_(&renderer), model_(model) {
  GLFWwindow* w = window.handle();
  glfwSetWindowUserPointer(w, this);
  glfwSetKeyCallback(
      w, [](GLFWwindow* win, int key, int, int action, int mods) { input_of(win)->on_key(key, action, mods); });
  glfwSetMouseButtonCallback(
      w, [](GLFWwindow* win, int button, int action, int) { input_of(win)->on_button(button, action); });
  glfwSetCursorPosCallback(w, [](GLFWwindow* win, double x, double y) { input_of(win)->on_move(x, y); });
  glfwSetScrollCallback(w, [](GLFWwindow* win, double, double dy) { input_of(win)->on_scroll(dy); });
}

ViewInput::~ViewInput() {
  GLFWwindow* w = window_->handle();
  glfwSetKeyCallback(w, nullptr);
  glfwSetMouseButtonCallback(w, nullptr);
  glfwSetCursorPosCallback(w, nullptr);
  glfwSetScrollCallback(w, nullptr);
  glfwSetWindowUserPointer(w, nullptr);
}

bool ViewInput::take_step() {
  const bool step = step_;
  step_ = false;
  return step;
}

void ViewInput::on_key(int key, int action, int /*mods*/) {
  if (action == GLFW_RELEASE) return;
  RenderSettings& s = renderer_->settings();
  switch (key) {
    case GLFW_KEY_ESCAPE:
      window_->request_close();
      break;
    case GLFW_KEY_SPACE:
      if (action == GLFW_PRESS) frozen_ = !frozen_;
      break;
    case GLFW_KEY_RIGHT:
      if (frozen_) step_ = true;
      break;
    case GLFW_KEY_C:
      if (action == GLFW_PRESS) s.contacts = !s.contacts;
      break;
    case GLFW_KEY_T:
      if (action == GLFW_PRESS) s.layers[1] = !s.layers[1];
      break;
    case GLFW_KEY_L:
      if (action == GLFW_PRESS) s.layers[2] = !s.layers[2];
      break;
    case GLFW_KEY_S:
      if (action == GLFW_PRESS) s.stereo = !s.stereo;
      break;
    case GLFW_KEY_BACKSPACE:
      renderer_->reset_camera();
      break;
    case GLFW_KEY_F1:
      if (action == GLFW_PRESS) help_ = !help_;
      break;
    default:
      break;
  }
}

void ViewInput::on_button(int button, int action) {
  const bool down = action == GLFW_PRESS;
  if (button == GLFW_MOUSE_BUTTON_LEFT) left_ = down;
  if (button == GLFW_MOUSE_BUTTON_RIGHT) right_ = down;
  if (button == GLFW_MOUSE_BUTTON_MIDDLE) middle_ = down;
  glfwGetCursorPos(window_->handle(), &last_x_, &last_y_);
}

void ViewInput::on_move(double x, double y) {
  const double dx = x - last_x_;
  const double dy = y - last_y_;
  last_x_ = x;
  last_y_ = y;
  if (!left_ && !right_ && !middle_) return;
  int width = 0, height = 0;
  window_->window_size(width, height);
  if (height <= 0) return;
  GLFWwindow* w = window_->handle();
  const bool shift =
      glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS || glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
  int action = mjMOUSE_ZOOM;
  if (right_) {
    action = shift ? mjMOUSE_MOVE_H : mjMOUSE_MOVE_V;
  } else if (left_) {
    action = shift ? mjMOUSE_ROTATE_H : mjMOUSE_ROTATE_V;
  }
  // a model's fixed camera does not move: dragging leaves it for the free camera where it is
  mjvCamera& cam = renderer_->camera();
  if (cam.type == mjCAMERA_FIXED) cam.type = mjCAMERA_FREE;
  mjv_moveCamera(model_, action, dx / height, dy / height, &renderer_->scene(), &cam);
}

void ViewInput::on_scroll(double dy) {
  mjvCamera& cam = renderer_->camera();
  if (cam.type == mjCAMERA_FIXED) cam.type = mjCAMERA_FREE;
  mjv_moveCamera(model_, mjMOUSE_ZOOM, 0, -0.05 * dy, &renderer_->scene(), &cam);
}

}  // namespace teleop::view
