#pragma once
// The keys and the mouse of `teleop view`: the camera as in MuJoCo's `simulate` (left drag
// rotates, right drag moves, middle drag or the wheel zooms; Shift: in the horizontal plane), and
// the view's own keys (view_input.cpp's kKeyHelp).

#include "teleop/view/gl_window.h"
#include "teleop/view/scene_renderer.h"

namespace teleop::view {

/// One line per key, for the help overlay and docs/view.md.
extern const char* const kKeyHelp;

class ViewInput {
 public:
  /// Takes over the window's input callbacks; both must outlive this.
  ViewInput(GlWindow& window, SceneRenderer& renderer, const mjModel* model);
  ~ViewInput();
  ViewInput(const ViewInput&) = delete;
  ViewInput& operator=(const ViewInput&) = delete;

  /// Space: the picture stays as it is while the bus goes on.
  bool frozen() const { return frozen_; }
  /// Right arrow while frozen: one update from the bus; true once per press.
  bool take_step();
  bool help_shown() const { return help_; }

  // the callbacks' work (public for them)
  void on_key(int key, int action, int mods);
  void on_button(int button, int action);
  void on_move(double x, double y);
  void on_scroll(double dy);

 private:
  GlWindow* window_;
  SceneRenderer* renderer_;
  const mjModel* model_;
  bool frozen_ = false;
  bool step_ = false;
  bool help_ = false;
  bool left_ = false, right_ = false, middle_ = false;
  double last_x_ = 0, last_y_ = 0;
};

}  // namespace teleop::view
