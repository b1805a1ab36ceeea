#pragma once
// SIGINT/SIGTERM turn into a flag the control loop polls (the handler only stores atomics), or,
// before a node has joined the network, end the process at once.

#include <cstdint>

namespace teleop::runtime {

/// Installs the handlers for SIGINT and SIGTERM (idempotent).
void install_shutdown_handlers();
/// While on, SIGINT and SIGTERM end the process at once with exit code 128 + signal (one line on
/// stderr) instead of raising the flag. For a node's phase before it joins the network: its long
/// steps (parsing YAML, compiling a MuJoCo model) cannot poll a flag, and it holds nothing a clean
/// shutdown would save (no participant, no file written). Off by default; switch it off before
/// creating anything the flag's clean shutdown must close.
void set_signals_exit_at_once(bool at_once);
/// True once SIGINT or SIGTERM arrived (or request_shutdown() was called). Real-time safe.
bool shutdown_requested();
/// Monotonic time [ns] the request arrived; 0 when none.
int64_t shutdown_requested_at_ns();
/// Requests shutdown from inside the program (e.g. the run's duration is over).
void request_shutdown();

}  // namespace teleop::runtime
