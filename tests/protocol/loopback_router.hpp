#pragma once
// LoopbackRouter: the server end of a real ROUTER/DEALER pair on
// tcp://127.0.0.1:* (port read back), scripted by a test. Create it on the
// test thread, then use it only from the one thread that plays the server.
#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include <zmq.hpp>

#include "dfc/protocol/codec.hpp"
#include "dfc/protocol/transport.hpp"

namespace dfc::protocol::testing {

class LoopbackRouter {
 public:
  explicit LoopbackRouter(zmq::context_t& context) : socket_(context, zmq::socket_type::router) {
    configure_socket(socket_, Limits{});
    socket_.bind("tcp://127.0.0.1:*");
    endpoint_ = socket_.get(zmq::sockopt::last_endpoint);
  }

  [[nodiscard]] const std::string& endpoint() const noexcept { return endpoint_; }

  struct Request {
    zmq::message_t routing_id;
    std::vector<std::string> frames;  ///< as received, header first
    [[nodiscard]] Message decoded() const {
      std::vector<std::span<const std::byte>> views;
      for (const auto& f : frames) views.emplace_back(reinterpret_cast<const std::byte*>(f.data()), f.size());
      return decode(views, Limits{});
    }
  };

  /// The next request, or nullopt after `timeout`.
  std::optional<Request> receive(std::chrono::milliseconds timeout = std::chrono::seconds(5)) {
    auto frames = receive_frames(socket_, timeout);
    if (!frames || frames->size() < 2) return std::nullopt;
    Request request{std::move(frames->front()), {}};
    for (std::size_t i = 1; i < frames->size(); ++i) request.frames.push_back((*frames)[i].to_string());
    return request;
  }

  void reply(const Request& to, const Message& reply) { send_message(socket_, reply, &to.routing_id); }

  /// A reply of `type` to `request`'s seq.
  static Message answer(const Message& request, std::string type) {
    Message reply;
    reply.type = std::move(type);
    reply.reply_to = request.seq;
    return reply;
  }

 private:
  zmq::socket_t socket_;
  std::string endpoint_;
};

}  // namespace dfc::protocol::testing
