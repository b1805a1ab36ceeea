#pragma once
// Ends a callback-mode reader's calls into its owner when the owner goes. A reader's callback
// runs on a Fast DDS thread for as long as the participant lives, and the participant outlives
// the objects whose members the callbacks touch (a node's logic is destroyed before its
// participant): without the gate a callback still running while its owner is destroyed reads
// freed memory (ASan saw CommandAuthority::judge do so as a leader stopped).

#include <functional>
#include <memory>
#include <mutex>

namespace teleop::transport {

class CallbackGate {
 public:
  CallbackGate() = default;
  ~CallbackGate() { close(); }
  CallbackGate(const CallbackGate&) = delete;
  CallbackGate& operator=(const CallbackGate&) = delete;

  /// `callback`, run only while the gate is open (Participant::make_reader's callback mode).
  template <typename... Args>
  std::function<void(Args...)> guard(std::function<void(Args...)> callback) const {
    return [state = state_, cb = std::move(callback)](Args... args) {
      std::lock_guard lock(state->mutex);
      if (state->open) cb(args...);
    };
  }

  /// Returns once no guarded callback runs, and none will again. The owner's destructor calls it
  /// before any of its members goes.
  void close() {
    std::lock_guard lock(state_->mutex);
    state_->open = false;
  }

 private:
  struct State {
    std::mutex mutex;
    bool open = true;
  };
  std::shared_ptr<State> state_ = std::make_shared<State>();
};

}  // namespace teleop::transport
