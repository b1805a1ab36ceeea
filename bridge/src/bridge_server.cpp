#include "bridge_server.h"

#include <chrono>
#include <mutex>

#include "teleop/common/clock.h"

namespace teleop::bridge {
namespace {

// how often each client's queue is offered to its socket again once the socket was full
constexpr std::chrono::milliseconds kPumpPeriod{10};

}  // namespace

BridgeServer::BridgeServer(const BridgeOptions& options, FILE* log)
    : options_(options),
      log_(log),
      session_id_(std::to_string(std::chrono::system_clock::now().time_since_epoch().count())),
      server_(WsSettings{kSubprotocol},
              WsHandlers{[this](ClientId id, const std::string& remote) { opened(id, remote); },
                         [this](ClientId id, const std::string& payload, bool binary) { received(id, payload, binary); },
                         [this](ClientId id) { closed(id); }}) {}

BridgeServer::~BridgeServer() { stop(); }

uint16_t BridgeServer::start() {
  const uint16_t port = server_.listen(options_.address, options_.port);
  server_.start(kPumpPeriod, [this] { pump_all(); });
  return port;
}

void BridgeServer::stop() { server_.stop(); }

uint32_t BridgeServer::add_channel(Channel channel_to_add) {
  const Channel channel = channels_.add(std::move(channel_to_add));
  server_.post([this, channel] {
    const std::string advertise = advertise_json({channel});
    std::shared_lock lock(clients_mutex_);
    for (const auto& entry : clients_) server_.send(entry.first, advertise, false);
  });
  return channel.id;
}

void BridgeServer::publish(uint32_t channel_id, const uint8_t* payload, size_t size, int64_t receive_ns) {
  const int64_t now_ns = monotonic_now_ns();
  std::shared_lock lock(clients_mutex_);
  for (const auto& [id, session] : clients_) {
    // the first frame in an empty queue wakes the sender; later ones ride along
    if (session->offer(channel_id, payload, size, receive_ns, now_ns)) server_.post([this, id = id] { pump(id); });
  }
}

std::shared_ptr<ClientSession> BridgeServer::client(ClientId id) const {
  std::shared_lock lock(clients_mutex_);
  const auto it = clients_.find(id);
  return it == clients_.end() ? nullptr : it->second;
}

void BridgeServer::opened(ClientId id, const std::string& remote) {
  {
    std::unique_lock lock(clients_mutex_);
    clients_[id] = std::make_shared<ClientSession>(remote, options_.max_rate_hz, options_.queue_capacity);
  }
  server_.send(id, server_info_json("teleop bridge", session_id_), false);
  server_.send(id, advertise_json(channels_.all()), false);
  std::fprintf(log_, "client %llu (%s) connected\n", static_cast<unsigned long long>(id), remote.c_str());
  std::fflush(log_);
}

void BridgeServer::received(ClientId id, const std::string& payload, bool binary) {
  const std::shared_ptr<ClientSession> session = client(id);
  if (!session) return;
  if (binary) return warn(id, "binary messages are not accepted: this bridge is read-only");
  const ClientRequest request = parse_client_request(payload);
  switch (request.op) {
    case ClientRequest::Op::kSubscribe: return subscribe(id, *session, request);
    case ClientRequest::Op::kUnsubscribe: return unsubscribe(id, *session, request);
    case ClientRequest::Op::kUnsupported:
      return warn(id, "op '" + request.detail + "' is not supported: this bridge is read-only");
    case ClientRequest::Op::kMalformed: return warn(id, "malformed message: " + request.detail);
  }
}

void BridgeServer::subscribe(ClientId id, ClientSession& session, const ClientRequest& request) {
  for (const auto& [subscription_id, channel_id] : request.subscriptions) {
    if (!channels_.contains(channel_id)) {
      warn(id, "no channel " + std::to_string(channel_id));
      continue;
    }
    if (const auto error = session.subscribe(subscription_id, channel_id)) warn(id, *error);
  }
}

void BridgeServer::unsubscribe(ClientId id, ClientSession& session, const ClientRequest& request) {
  for (const uint32_t subscription_id : request.unsubscriptions) {
    if (const auto error = session.unsubscribe(subscription_id)) warn(id, *error);
  }
}

void BridgeServer::warn(ClientId id, const std::string& message) {
  server_.send(id, status_json(StatusLevel::kWarning, message), false);
}

void BridgeServer::closed(ClientId id) {
  std::shared_ptr<ClientSession> session;
  {
    std::unique_lock lock(clients_mutex_);
    const auto it = clients_.find(id);
    if (it == clients_.end()) return;
    session = it->second;
    clients_.erase(it);
  }
  slow_.erase(id);
  const ClientStats s = session->stats();
  std::fprintf(log_, "client %llu (%s) left: sent %llu, dropped %llu (queue full), limited %llu (rate limit)\n",
               static_cast<unsigned long long>(id), session->remote().c_str(),
               static_cast<unsigned long long>(s.sent), static_cast<unsigned long long>(s.dropped),
               static_cast<unsigned long long>(s.limited));
  std::fflush(log_);
}

void BridgeServer::pump(ClientId id) {
  if (const std::shared_ptr<ClientSession> session = client(id)) send_queued(id, *session);
}

void BridgeServer::send_queued(ClientId id, ClientSession& session) {
  // hand frames over only while the client's socket takes them: the rest wait in the bounded queue
  while (server_.buffered_bytes(id) < options_.max_buffered_bytes) {
    std::optional<std::string> frame = session.queue().pop();
    if (!frame) return;
    server_.send(id, *frame, true);
    session.count_sent();
  }
}

void BridgeServer::pump_all() {
  std::vector<std::pair<ClientId, std::shared_ptr<ClientSession>>> sessions;
  {
    std::shared_lock lock(clients_mutex_);
    sessions.assign(clients_.begin(), clients_.end());
  }
  for (const auto& [id, session] : sessions) {
    send_queued(id, *session);
    warn_if_slow(id, *session);
  }
}

// once per client, from the server's thread (the bus's threads never write the log)
void BridgeServer::warn_if_slow(ClientId id, const ClientSession& session) {
  if (slow_.count(id) > 0 || session.stats().dropped == 0) return;
  slow_.insert(id);
  std::fprintf(log_, "client %llu (%s) is not keeping up: its oldest frames are dropped (queue of %zu)\n",
               static_cast<unsigned long long>(id), session.remote().c_str(), options_.queue_capacity);
  std::fflush(log_);
}

}  // namespace teleop::bridge
