#include "dfc/protocol/heartbeat_responder.hpp"

#include <iostream>

#include "dfc/common/work_progress.hpp"
#include "dfc/protocol/heartbeat.hpp"
#include "dfc/protocol/transport.hpp"

namespace dfc::protocol {

namespace {

constexpr auto kStopSlice = std::chrono::milliseconds(100);  // how soon the thread sees a stop request

std::int64_t steady_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

Message answer(std::span<const std::span<const std::byte>> frames, const Limits& limits, const Liveness& liveness) {
  Message request;
  try {
    request = decode(frames, limits);
  } catch (const DecodeError& e) {
    return make_error(e.seq(), e.code(), e.what());
  }
  if (request.type != type::ping)
    return make_error(request.seq, ErrorCode::unknown_type,
                      "the heartbeat endpoint answers only 'ping', not '" + request.type.substr(0, 64) + "'; send other requests to the main endpoint");
  Message pong;
  pong.type = std::string(type::pong);
  pong.reply_to = request.seq;
  const double busy = liveness.busy_seconds();
  pong.body = {{heartbeat::handled_key, liveness.handled()},
               {heartbeat::step_key, liveness.step()},
               {heartbeat::busy_key, busy < 0.0 ? nlohmann::json(nullptr) : nlohmann::json(busy)}};
  if (liveness.reports_progress()) pong.body[heartbeat::progress_key] = work_progress::current();
  return pong;
}

/// The heartbeat thread: answers every message on `socket` until asked to stop.
void answer_pings(std::stop_token stop, zmq::socket_t socket, const Liveness& liveness, const std::string& version) noexcept {
  const Limits limits = heartbeat::message_limits();
  std::int64_t next_seq = 0;  // the heartbeat's replies are numbered apart from the main socket's (SPEC.md §9.1)
  try {
    while (!stop.stop_requested()) {
      const auto frames = receive_frames(socket, kStopSlice);
      if (!frames || frames->size() < 2) continue;  // [routing id, frames...]; nothing to answer
      Message reply = answer(frame_views(*frames, 1), limits, liveness);
      reply.version = version;
      reply.seq = next_seq++;
      send_message(socket, reply, &frames->front());
    }
  } catch (const std::exception& e) {
    // The server goes on; a client then sees no pong and declares it hung.
    std::cerr << "heartbeat thread stopped: " << e.what() << "\n";
  }
}

}  // namespace

void Liveness::begin_request() noexcept { busy_since_ns_.store(steady_ns(), std::memory_order_relaxed); }

void Liveness::end_request(std::int64_t step) noexcept {
  step_.store(step, std::memory_order_relaxed);
  handled_.fetch_add(1, std::memory_order_relaxed);
  busy_since_ns_.store(-1, std::memory_order_relaxed);
}

double Liveness::busy_seconds() const noexcept {
  const std::int64_t since = busy_since_ns_.load(std::memory_order_relaxed);
  return since < 0 ? -1.0 : static_cast<double>(steady_ns() - since) * 1e-9;
}

HeartbeatResponder::HeartbeatResponder(zmq::context_t& context, const std::string& bind, const Liveness& liveness, std::string version,
                                       const std::optional<authentication::CurveKeyPair>& keys) {
  zmq::socket_t socket(context, zmq::socket_type::router);
  configure_socket(socket, heartbeat::message_limits());
  authentication::secure_server_socket(socket, keys);
  socket.bind(bind);
  endpoint_ = socket.get(zmq::sockopt::last_endpoint);
  // The socket moves to the thread, which alone uses it from now on (a
  // ZeroMQ socket may change threads across the full barrier of a thread start).
  thread_ = std::jthread(answer_pings, std::move(socket), std::cref(liveness), std::move(version));
}

}  // namespace dfc::protocol
