#include "dfc/protocol/transport.hpp"

#include <algorithm>

namespace dfc::protocol {

void configure_socket(zmq::socket_t& socket, const Limits& limits) {
  socket.set(zmq::sockopt::linger, 0);
  const std::size_t largest = std::max(limits.max_header_bytes, limits.max_array_bytes);
  socket.set(zmq::sockopt::maxmsgsize, static_cast<int64_t>(2 * largest + 4096));
}

void send_message(zmq::socket_t& socket, const Message& message, const zmq::message_t* routing_id) {
  if (routing_id != nullptr) {
    zmq::message_t id(routing_id->data(), routing_id->size());
    socket.send(id, zmq::send_flags::sndmore);
  }
  const std::string header = encode_header(message);
  const auto more = [&](std::size_t index) { return index < message.arrays.size() ? zmq::send_flags::sndmore : zmq::send_flags::none; };
  socket.send(zmq::buffer(header), more(0));
  for (std::size_t i = 0; i < message.arrays.size(); ++i) {
    const auto& bytes = message.arrays[i].bytes;
    socket.send(zmq::const_buffer(bytes.data(), bytes.size()), more(i + 1));
  }
}

std::optional<std::vector<zmq::message_t>> receive_frames(zmq::socket_t& socket, std::chrono::milliseconds timeout) {
  zmq::pollitem_t item{socket.handle(), 0, ZMQ_POLLIN, 0};
  try {
    if (zmq::poll(&item, 1, timeout) == 0) return std::nullopt;
  } catch (const zmq::error_t& e) {
    // A signal (Ctrl-C) interrupted the wait: report "nothing yet" so the
    // caller's loop can look at its stop flag and deadline.
    if (e.num() == EINTR) return std::nullopt;
    throw;
  }
  std::vector<zmq::message_t> frames;
  // A multipart message is delivered atomically (all parts or none), so once
  // the first part is readable the rest are already here.
  do {
    zmq::message_t frame;
    if (!socket.recv(frame, zmq::recv_flags::none)) return std::nullopt;
    frames.push_back(std::move(frame));
  } while (frames.back().more());
  return frames;
}

std::vector<std::span<const std::byte>> frame_views(const std::vector<zmq::message_t>& frames, std::size_t first) {
  std::vector<std::span<const std::byte>> views;
  for (std::size_t i = first; i < frames.size(); ++i)
    views.emplace_back(static_cast<const std::byte*>(frames[i].data()), frames[i].size());
  return views;
}

}  // namespace dfc::protocol
