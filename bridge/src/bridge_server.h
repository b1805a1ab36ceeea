#pragma once
// The bridge's server: the channels, the clients with their subscriptions and queues, and the
// WebSocket server. Samples come in on Fast DDS threads (dispatch: a short lock per client, never
// the network); frames leave on the server's thread, only as fast as each client's socket takes
// them.

#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <shared_mutex>
#include <string>

#include "channel_table.h"
#include "client_session.h"
#include "teleop/bridge/bridge.h"
#include "ws_server.h"

namespace teleop::bridge {

class BridgeServer {
 public:
  BridgeServer(const BridgeOptions& options, FILE* log);
  ~BridgeServer();

  /// Listens and starts serving; returns the port.
  uint16_t start();
  /// Closes every connection (each client's tally is logged) and stops.
  void stop();

  /// A new channel (its id is chosen here), advertised to every client; returns its id.
  uint32_t add_channel(Channel channel);
  /// From any thread (a Fast DDS thread for the bus's samples): a message of `channel_id`,
  /// received at `receive_ns` (CLOCK_REALTIME), for every client subscribed to it.
  void publish(uint32_t channel_id, const uint8_t* payload, size_t size, int64_t receive_ns);

 private:
  std::shared_ptr<ClientSession> client(ClientId id) const;
  void opened(ClientId id, const std::string& remote);
  void received(ClientId id, const std::string& payload, bool binary);
  void closed(ClientId id);
  void subscribe(ClientId id, ClientSession& session, const ClientRequest& request);
  void unsubscribe(ClientId id, ClientSession& session, const ClientRequest& request);
  void warn(ClientId id, const std::string& message);
  void pump(ClientId id);
  void send_queued(ClientId id, ClientSession& session);
  void pump_all();
  void warn_if_slow(ClientId id, const ClientSession& session);

  const BridgeOptions options_;
  FILE* log_;
  const std::string session_id_;
  ChannelTable channels_;
  mutable std::shared_mutex clients_mutex_;
  std::map<ClientId, std::shared_ptr<ClientSession>> clients_;
  // the clients told to be too slow (in the log), on the server's thread
  std::set<ClientId> slow_;
  WsServer server_;
};

}  // namespace teleop::bridge
