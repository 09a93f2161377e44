#pragma once
// The client's side of the heartbeat (SPEC.md §9.1, 1.6): while a client
// waits for a server's reply it pings the server's heartbeat endpoint on a
// socket of its own; a server that answers neither the request nor any ping
// for the hang timeout is hung (stopped, frozen, or its process swapped out),
// however long its deadline. A server busy in a long advance answers the pings.
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include <zmq.hpp>

#include <nlohmann/json.hpp>

namespace dfc::protocol {

class HeartbeatMonitor {
 public:
  /// Connects a DEALER socket to the heartbeat at `endpoint`, with the
  /// server's key when it has one (SPEC.md §2.1). A server is hung once a
  /// ping has gone unanswered for `hang_timeout` (> 0).
  HeartbeatMonitor(zmq::context_t& context, const std::string& endpoint, std::chrono::milliseconds hang_timeout,
                   const std::optional<std::string>& server_key);

  /// A wait for a reply begins: the silence is counted from now (the last
  /// reply, or the client's own work, came just before).
  void begin_wait();
  /// Sends a ping when one is due (every second, or a quarter of the hang
  /// timeout if that is shorter, from one interval into the wait) and reads
  /// the pongs that arrived. Returns
  /// true while the server is alive: a pong to a ping of this wait came less
  /// than the hang timeout ago (or the wait is younger than that).
  [[nodiscard]] bool poll();

  /// "no pong from its heartbeat (tcp://127.0.0.1:40124) for 10.0 s; the last one
  /// said 57 requests handled, step 1200, busy for 3.1 s".
  [[nodiscard]] std::string silence_description() const;
  [[nodiscard]] std::chrono::milliseconds hang_timeout() const noexcept { return hang_timeout_; }
  [[nodiscard]] const std::string& endpoint() const noexcept { return endpoint_; }

 private:
  using Clock = std::chrono::steady_clock;
  void read_pongs(Clock::time_point now);

  zmq::socket_t socket_;
  std::string endpoint_;
  std::chrono::milliseconds hang_timeout_;
  std::chrono::milliseconds interval_;
  std::int64_t next_seq_ = 1;
  std::int64_t first_seq_of_wait_ = 1;  ///< pongs to earlier pings (of an earlier wait) prove nothing now
  Clock::time_point last_ping_{};
  Clock::time_point last_life_{};       ///< the wait's start or its latest pong
  bool ever_answered_ = false;
  nlohmann::json last_pong_body_;       ///< the body of the latest pong, for the message
};

}  // namespace dfc::protocol
