#include "dfc/protocol/transport.hpp"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <limits>

#include "dfc/common/echo.hpp"

namespace dfc::protocol {

void configure_socket(zmq::socket_t& socket, const Limits& limits) {
  socket.set(zmq::sockopt::linger, 0);
  // A send never blocks. A DEALER whose peer failed the security handshake
  // (a client without the server's key, or with another) has no pipe left,
  // and libzmq would block in zmq_send for ever; a DEALER whose peer stopped
  // reading blocks at the high-water mark. send_message reports it instead.
  socket.set(zmq::sockopt::sndtimeo, 0);
  const std::size_t largest = std::max(limits.max_header_bytes, limits.max_array_bytes);
  socket.set(zmq::sockopt::maxmsgsize, static_cast<int64_t>(2 * largest + 4096));
}

std::optional<std::string> endpoint_problem(std::string_view endpoint) {
  const std::string expected = "expected a ZeroMQ endpoint \"tcp://HOST:PORT\" (e.g. \"tcp://127.0.0.1:5555\") or \"ipc://PATH\", got \"" +
                               echoed(endpoint, kMaxEchoedPathBytes) + "\"";
  if (endpoint.starts_with("ipc://")) {
    if (endpoint.size() == 6) return expected;
    return std::nullopt;
  }
  if (!endpoint.starts_with("tcp://")) return expected;
  const std::string_view address = endpoint.substr(6);
  const auto colon = address.rfind(':');
  if (colon == std::string_view::npos || colon == 0) return expected + ": the host or port is missing";
  const std::string_view port_text = address.substr(colon + 1);
  unsigned port = 0;
  const auto [end, error] = std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
  if (port_text.empty() || error != std::errc() || end != port_text.data() + port_text.size() || port < 1 || port > 65535)
    return expected + ": the port must be a number 1..65535";
  return std::nullopt;
}

bool send_message(zmq::socket_t& socket, const Message& message, const zmq::message_t* routing_id) {
  if (routing_id != nullptr) {
    zmq::message_t id(routing_id->data(), routing_id->size());
    if (!socket.send(id, zmq::send_flags::sndmore)) return false;
  }
  const std::string header = encode_header(message);
  const auto more = [&](std::size_t index) { return index < message.arrays.size() ? zmq::send_flags::sndmore : zmq::send_flags::none; };
  // Only the first frame can be refused: once it is queued, libzmq takes the
  // rest of the message into the same pipe (a multipart message is atomic).
  if (!socket.send(zmq::buffer(header), more(0))) return false;
  for (std::size_t i = 0; i < message.arrays.size(); ++i) {
    const auto& bytes = message.arrays[i].bytes;
    socket.send(zmq::const_buffer(bytes.data(), bytes.size()), more(i + 1));
  }
  return true;
}

std::optional<std::vector<zmq::message_t>> receive_frames(zmq::socket_t& socket, std::chrono::milliseconds timeout) {
  // A blocking receive with a timeout, not zmq_poll + receive: zmq_poll asks
  // the socket for its events before and after it waits, and each ask is a
  // poll(2) and a getpid(2) inside libzmq; on a virtual machine, where a
  // system call costs microseconds, that was a third of an exchange's
  // overhead (bench/exchange_overhead.sh).
  socket.set(zmq::sockopt::rcvtimeo, static_cast<int>(std::clamp<std::int64_t>(timeout.count(), 0, std::numeric_limits<int>::max())));
  std::vector<zmq::message_t> frames;
  try {
    zmq::message_t first;
    if (!socket.recv(first, zmq::recv_flags::none)) return std::nullopt;  // nothing within the timeout
    frames.push_back(std::move(first));
  } catch (const zmq::error_t& e) {
    // A signal (Ctrl-C) interrupted the wait: report "nothing yet" so the
    // caller's loop can look at its stop flag and deadline.
    if (e.num() == EINTR) return std::nullopt;
    throw;
  }
  // A multipart message is delivered atomically (all parts or none), so once
  // the first part is here the rest are too.
  while (frames.back().more()) {
    zmq::message_t frame;
    if (!socket.recv(frame, zmq::recv_flags::dontwait)) return std::nullopt;
    frames.push_back(std::move(frame));
  }
  return frames;
}

std::vector<std::span<const std::byte>> frame_views(const std::vector<zmq::message_t>& frames, std::size_t first) {
  std::vector<std::span<const std::byte>> views;
  for (std::size_t i = first; i < frames.size(); ++i)
    views.emplace_back(static_cast<const std::byte*>(frames[i].data()), frames[i].size());
  return views;
}

}  // namespace dfc::protocol
