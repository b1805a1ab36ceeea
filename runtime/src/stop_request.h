#pragma once
// A stop request for a helper thread that works in periods (the flow watch, the trace's writer;
// never the control loop): its sleep between periods ends the moment stop is requested, so that
// joining the thread costs no part of a period. Shutdown within 100 ms depends on it.

#include <chrono>
#include <condition_variable>
#include <mutex>

namespace teleop::runtime {

class StopRequest {
 public:
  /// Sleeps for `period`, less when stop is requested meanwhile; true once stop was requested.
  bool wait_for(std::chrono::nanoseconds period) {
    std::unique_lock<std::mutex> lock(mutex_);
    return wake_.wait_for(lock, period, [this] { return requested_; });
  }
  /// Asks the thread to stop and wakes it.
  void request() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      requested_ = true;
    }
    wake_.notify_all();
  }

 private:
  std::mutex mutex_;
  std::condition_variable wake_;
  bool requested_ = false;
};

}  // namespace teleop::runtime
