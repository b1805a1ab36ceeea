#pragma once
// The pinger's side of the echo re-execution protocol: the echo is this executable re-executed
// with `--role echo --variant NAME --domain D --max-seconds S [--pki DIR] --ready-fd FD`; it
// writes one line "ready[ PORT]\n" to FD once it answers (PORT: the raw UDP echo's), and exits
// on SIGTERM, on its parent's death or after --max-seconds.

#include <sys/types.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "roundtrip.h"

namespace teleop::bench {

/// The arguments that start the echo of variant `v` (all but --ready-fd, which EchoProcess adds).
std::vector<std::string> echo_args(Variant v, const Options& opt);

/// A child process running this executable with `--role echo`. Killed and reaped by the
/// destructor on every path.
class EchoProcess {
 public:
  explicit EchoProcess(const std::vector<std::string>& role_args);
  ~EchoProcess() { stop(); }
  EchoProcess(const EchoProcess&) = delete;
  EchoProcess& operator=(const EchoProcess&) = delete;

  /// Waits for the echo's "ready ..." line; returns what follows "ready". Throws on timeout,
  /// on the echo's death and on a stop signal.
  std::string wait_ready(int64_t deadline_mono_ns);

  /// CPU time the echo has used so far; -1 when it cannot be read.
  int64_t cpu_ns() const { return pid_ > 0 ? process_cpu_ns(pid_) : -1; }

  /// Throws if the echo has died.
  void check_alive();

  /// SIGTERM, up to 3 s to exit cleanly, then SIGKILL; always reaps.
  void stop();

 private:
  std::string exit_description();

  pid_t pid_ = -1;
  int ready_fd_ = -1;
  std::optional<int> status_;
};

}  // namespace teleop::bench
