#include "ws_server.h"

#define ASIO_STANDALONE
#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

#include <algorithm>
#include <map>
#include <stdexcept>
#include <thread>

namespace teleop::bridge {

using Endpoint = websocketpp::server<websocketpp::config::asio>;
using Handle = websocketpp::connection_hdl;

struct WsServer::Impl {
  WsSettings settings;
  WsHandlers handlers;
  Endpoint endpoint;
  std::map<Handle, ClientId, std::owner_less<Handle>> ids;
  std::map<ClientId, Handle> handles;
  ClientId next_id = 1;
  std::thread thread;
  std::chrono::milliseconds period{10};
  std::function<void()> tick;
  bool stopping = false;

  Impl(WsSettings chosen, WsHandlers callbacks) : settings(std::move(chosen)), handlers(std::move(callbacks)) {
    endpoint.clear_access_channels(websocketpp::log::alevel::all);
    endpoint.clear_error_channels(websocketpp::log::elevel::all);
    endpoint.init_asio();
    endpoint.set_reuse_addr(true);
    endpoint.set_max_message_size(settings.max_client_message);
    // a dead client must not hold the shutdown up
    endpoint.set_close_handshake_timeout(500);
    endpoint.set_socket_init_handler([this](Handle, asio::ip::tcp::socket& socket) { init_socket(socket); });
    endpoint.set_validate_handler([this](Handle h) { return select_subprotocol(h); });
    endpoint.set_open_handler([this](Handle h) { opened(h); });
    endpoint.set_close_handler([this](Handle h) { closed(h); });
    endpoint.set_fail_handler([this](Handle h) { closed(h); });
    endpoint.set_message_handler([this](Handle h, Endpoint::message_ptr m) { received(h, m); });
  }

  void init_socket(asio::ip::tcp::socket& socket) const {
    asio::error_code ignored;
    socket.set_option(asio::ip::tcp::no_delay(true), ignored);
    socket.set_option(asio::socket_base::send_buffer_size(settings.socket_send_buffer), ignored);
  }

  bool select_subprotocol(Handle h) {
    const Endpoint::connection_ptr connection = endpoint.get_con_from_hdl(h);
    const std::vector<std::string>& offered = connection->get_requested_subprotocols();
    if (std::find(offered.begin(), offered.end(), settings.subprotocol) == offered.end()) return false;
    connection->select_subprotocol(settings.subprotocol);
    return true;
  }

  void opened(Handle h) {
    const ClientId id = next_id++;
    ids[h] = id;
    handles[id] = h;
    handlers.on_open(id, endpoint.get_con_from_hdl(h)->get_remote_endpoint());
  }

  void closed(Handle h) {
    const auto it = ids.find(h);
    if (it == ids.end()) return;  // refused in the handshake: never opened
    const ClientId id = it->second;
    ids.erase(it);
    handles.erase(id);
    handlers.on_close(id);
  }

  void received(Handle h, const Endpoint::message_ptr& message) {
    const auto it = ids.find(h);
    if (it == ids.end()) return;
    handlers.on_message(it->second, message->get_payload(),
                        message->get_opcode() == websocketpp::frame::opcode::binary);
  }

  void arm_timer() {
    endpoint.set_timer(static_cast<long>(period.count()), [this](const websocketpp::lib::error_code& ec) {
      if (ec || stopping) return;
      tick();
      arm_timer();
    });
  }

  void close_all() {
    stopping = true;
    websocketpp::lib::error_code ignored;
    if (endpoint.is_listening()) endpoint.stop_listening(ignored);
    for (const auto& entry : handles) endpoint.close(entry.second, websocketpp::close::status::going_away, "", ignored);
  }
};

WsServer::WsServer(WsSettings settings, WsHandlers handlers)
    : impl_(std::make_unique<Impl>(std::move(settings), std::move(handlers))) {}

WsServer::~WsServer() { stop(); }

uint16_t WsServer::listen(const std::string& address, uint16_t port) {
  websocketpp::lib::error_code ec;
  impl_->endpoint.listen(address, std::to_string(port), ec);
  if (!ec) impl_->endpoint.start_accept(ec);
  if (ec) throw std::runtime_error("cannot listen on " + address + ":" + std::to_string(port) + ": " + ec.message());
  const asio::ip::tcp::endpoint local = impl_->endpoint.get_local_endpoint(ec);
  if (ec) throw std::runtime_error("cannot read the bound port: " + ec.message());
  return local.port();
}

void WsServer::start(std::chrono::milliseconds period, std::function<void()> tick) {
  impl_->period = period;
  impl_->tick = std::move(tick);
  impl_->arm_timer();
  impl_->thread = std::thread([this] { impl_->endpoint.run(); });
}

void WsServer::stop() {
  if (!impl_->thread.joinable()) return;
  post([this] { impl_->close_all(); });
  // run() returns once the connections are closed (or their close handshake timed out)
  impl_->thread.join();
}

void WsServer::post(std::function<void()> task) { asio::post(impl_->endpoint.get_io_service(), std::move(task)); }

void WsServer::send(ClientId client, const std::string& payload, bool binary) {
  const auto it = impl_->handles.find(client);
  if (it == impl_->handles.end()) return;
  websocketpp::lib::error_code ignored;  // a client gone: its close handler follows
  impl_->endpoint.send(it->second, payload,
                       binary ? websocketpp::frame::opcode::binary : websocketpp::frame::opcode::text, ignored);
}

size_t WsServer::buffered_bytes(ClientId client) const {
  const auto it = impl_->handles.find(client);
  if (it == impl_->handles.end()) return 0;
  websocketpp::lib::error_code ec;
  const Endpoint::connection_ptr connection = impl_->endpoint.get_con_from_hdl(it->second, ec);
  return ec ? 0 : connection->get_buffered_amount();
}

}  // namespace teleop::bridge
