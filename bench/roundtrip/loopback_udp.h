#pragma once
// The raw UDP variant's sockets on 127.0.0.1, for both the echo and the pinger.

#include <cstdint>

namespace teleop::bench {

/// An IPv4 UDP socket bound to 127.0.0.1:port (0 = any free port), with a receive timeout so
/// that blocking loops see their stop flags.
int loopback_udp_socket(uint16_t port);

/// The port a socket is bound to.
uint16_t local_port(int fd);

/// Connects a UDP socket to 127.0.0.1:port, so that send() and recv() talk to that peer only.
void connect_loopback(int fd, uint16_t port);

/// Closes the descriptor when it goes out of scope.
struct FdGuard {
  int fd;
  ~FdGuard();
};

}  // namespace teleop::bench
