#pragma once
// Thin cppzmq helpers: socket options, sending a Message as a multipart
// message, receiving with a deadline (SPEC.md §2). No protocol logic here.
#include <chrono>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <zmq.hpp>

#include "dfc/protocol/codec.hpp"
#include "dfc/protocol/message.hpp"

namespace dfc::protocol {

/// The start of the line a server prints on stdout once it listens (SPEC.md §2):
/// "DFC-LISTENING <endpoint>".
inline constexpr std::string_view kListeningMarker = "DFC-LISTENING ";

/// Linger 0 (abort paths never block, ZeroMQ ZMQ_LINGER, zmq_setsockopt(3)), a
/// send timeout of 0 (a send never blocks: see send_message) and a
/// transport-level cap on frame size well above the protocol limits, so that an
/// over-limit frame still reaches the codec and gets a TOO_LARGE reply while a
/// absurdly large one is dropped by libzmq before it is buffered.
void configure_socket(zmq::socket_t& socket, const Limits& limits);

/// Why a client cannot connect to `endpoint`, or nullopt: it must be
/// "tcp://HOST:PORT" (PORT 1..65535) or "ipc://PATH". libzmq would otherwise
/// throw a bare "Invalid argument" from connect.
[[nodiscard]] std::optional<std::string> endpoint_problem(std::string_view endpoint);

/// Sends `message` (header frame + one frame per array), preceded by
/// `routing_id` when replying from a ROUTER socket. False where the socket
/// could not queue it within its ZMQ_SNDTIMEO (0 after configure_socket): a
/// DEALER with no peer to take it (the peer refused the security handshake) or
/// at its high-water mark. A ROUTER drops a reply to a gone peer and says true.
bool send_message(zmq::socket_t& socket, const Message& message, const zmq::message_t* routing_id = nullptr);

/// Receives one whole multipart message, or nullopt if none arrives within `timeout`.
[[nodiscard]] std::optional<std::vector<zmq::message_t>> receive_frames(zmq::socket_t& socket, std::chrono::milliseconds timeout);

/// Byte views of frames[first..]; valid while `frames` lives.
[[nodiscard]] std::vector<std::span<const std::byte>> frame_views(const std::vector<zmq::message_t>& frames, std::size_t first);

}  // namespace dfc::protocol
