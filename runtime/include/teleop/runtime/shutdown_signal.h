#pragma once
// SIGINT/SIGTERM turn into a flag the control loop polls; the handler only stores atomics.

#include <cstdint>

namespace teleop::runtime {

/// Installs the handlers for SIGINT and SIGTERM (idempotent).
void install_shutdown_handlers();
/// True once SIGINT or SIGTERM arrived (or request_shutdown() was called). Real-time safe.
bool shutdown_requested();
/// Monotonic time [ns] the request arrived; 0 when none.
int64_t shutdown_requested_at_ns();
/// Requests shutdown from inside the program (e.g. the run's duration is over).
void request_shutdown();

}  // namespace teleop::runtime
