#pragma once
// The heartbeat (SPEC.md §9.1, 1.6): a second endpoint of a server, served by
// its own thread, that answers `ping` with `pong` at any time, also while the
// main thread is inside a long `configure` or `advance`. What both sides share:
// the version it appeared in, the pong's fields and the endpoint rules.
#include <optional>
#include <string>
#include <string_view>

#include "dfc/protocol/codec.hpp"

namespace dfc::protocol::heartbeat {

/// The minor version (of major 1) from which a server announces a heartbeat.
inline constexpr int kSinceMinor = 6;
/// The minor version from which every pong carries `progress` (the main
/// thread's work counter), and a client may declare a server whose counter
/// stands still stalled.
inline constexpr int kProgressSinceMinor = 8;

/// hello_ok.body field: the endpoint of the heartbeat socket.
inline constexpr std::string_view endpoint_key = "heartbeat_endpoint";

/// Fields of a heartbeat `pong`'s body: what shows the server is alive.
inline constexpr std::string_view handled_key = "handled";  ///< requests the main socket has answered so far
inline constexpr std::string_view step_key = "step";        ///< the session's step after the last answered request
inline constexpr std::string_view busy_key = "busy_s";      ///< s inside the request being handled now, null when idle
inline constexpr std::string_view progress_key = "progress";  ///< 1.8: work done by the main thread, never decreasing

/// What both ends of the heartbeat accept: a header alone (no arrays) of at
/// most 64 KiB, so that nothing bigger is ever buffered.
[[nodiscard]] Limits message_limits();

/// Where a server binds its heartbeat, next to its main socket's resolved
/// endpoint `main`: "tcp://HOST:PORT" -> "tcp://HOST:*" (any free port on the
/// same interface), "ipc://PATH" -> "ipc://PATH.heartbeat", "inproc://NAME" ->
/// "inproc://NAME.heartbeat"; nullopt for any other transport (no heartbeat).
[[nodiscard]] std::optional<std::string> bind_endpoint(std::string_view main);

/// Where a client connects for the heartbeat `announced` in hello_ok by a server
/// it reached at `main`: the announced endpoint, except that a wildcard tcp
/// host (a server bound to "tcp://*:*" announces "tcp://0.0.0.0:P") is
/// replaced by the host of `main`.
[[nodiscard]] std::string connect_endpoint(std::string_view announced, std::string_view main);

}  // namespace dfc::protocol::heartbeat
