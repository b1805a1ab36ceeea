#pragma once
// The WebSocket side of the bridge: websocketpp on standalone asio, one thread. Clients are known
// by a number; everything but post() and the constructor runs on (or must be called from) the
// server's thread: its handlers, posted functions and timers. This header stays C++17 (see
// CMakeLists.txt: websocketpp 0.8.2 does not compile as C++20, so its one source file is C++17).

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace teleop::bridge {

using ClientId = uint64_t;

struct WsHandlers {
  std::function<void(ClientId, const std::string& remote)> on_open;
  std::function<void(ClientId, const std::string& payload, bool binary)> on_message;
  std::function<void(ClientId)> on_close;
};

struct WsSettings {
  /// The one subprotocol accepted; a client that does not offer it is refused in the handshake.
  std::string subprotocol;
  /// The kernel's send buffer per client [bytes]: small, so that a client that stops reading
  /// shows up in buffered_bytes() (and the bridge's own bounded queue) within moments.
  int socket_send_buffer = 64 * 1024;
  /// The largest message a client may send [bytes].
  size_t max_client_message = 1 << 20;
};

class WsServer {
 public:
  WsServer(WsSettings settings, WsHandlers handlers);
  ~WsServer();

  /// Binds and listens; returns the port (with port 0: the one the system chose). Throws
  /// std::runtime_error naming the address.
  uint16_t listen(const std::string& address, uint16_t port);
  /// Runs the server's thread; `tick` runs on it every `period` until stop().
  void start(std::chrono::milliseconds period, std::function<void()> tick);
  /// Stops accepting, closes every connection, joins the thread.
  void stop();

  /// From any thread: runs `task` on the server's thread.
  void post(std::function<void()> task);

  // on the server's thread:
  void send(ClientId client, const std::string& payload, bool binary);
  /// What websocketpp holds for `client` beyond the kernel's buffer [bytes]; 0 for a client gone.
  size_t buffered_bytes(ClientId client) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace teleop::bridge
