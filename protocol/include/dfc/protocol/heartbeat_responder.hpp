#pragma once
// The server's side of the heartbeat (SPEC.md §9.1, 1.6): a ROUTER socket of
// its own, served by its own thread, that answers `ping` with `pong` whatever
// the main thread is doing. A process that is stopped (SIGSTOP), frozen or
// swapped out answers nothing; a busy one answers at once, and from 1.8 says
// how far its main thread has got (dfc::work_progress), so that one whose
// main thread deadlocked shows a counter that stands still.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>
#include <thread>

#include <zmq.hpp>

#include "dfc/protocol/authentication.hpp"

namespace dfc::protocol {

/// What the main thread has done, for the heartbeat's pongs: written by the
/// main thread around each request, read by the heartbeat thread; no lock.
class Liveness {
 public:
  /// `reports_progress`: whether the pongs carry the process's work counter
  /// (dfc::work_progress), as a server that declares 1.8 or later must.
  explicit Liveness(bool reports_progress = true) noexcept : reports_progress_(reports_progress) {}

  /// A request arrived and its handling starts.
  void begin_request() noexcept;
  /// Its reply was sent; the session is at `step`.
  void end_request(std::int64_t step) noexcept;

  [[nodiscard]] std::int64_t handled() const noexcept { return handled_.load(std::memory_order_relaxed); }
  [[nodiscard]] std::int64_t step() const noexcept { return step_.load(std::memory_order_relaxed); }
  /// Seconds inside the request being handled, or a negative number when idle.
  [[nodiscard]] double busy_seconds() const noexcept;
  [[nodiscard]] bool reports_progress() const noexcept { return reports_progress_; }

 private:
  bool reports_progress_;
  std::atomic<std::int64_t> handled_{0};
  std::atomic<std::int64_t> step_{0};
  std::atomic<std::int64_t> busy_since_ns_{-1};  ///< steady_clock, -1 when idle
};

class HeartbeatResponder {
 public:
  /// Binds a ROUTER socket at `bind` in `context` (before returning, so the
  /// endpoint can be announced) and answers pings from a thread of its own,
  /// speaking `version`, until destroyed. Destroy it before `context`. With
  /// `keys` it answers only clients that hold them, like the main socket (SPEC.md §2.1).
  HeartbeatResponder(zmq::context_t& context, const std::string& bind, const Liveness& liveness, std::string version,
                     const std::optional<authentication::CurveKeyPair>& keys);
  HeartbeatResponder(const HeartbeatResponder&) = delete;
  HeartbeatResponder& operator=(const HeartbeatResponder&) = delete;
  /// Stops the thread (it looks at its stop token every 100 ms) and joins it; its socket closes with it.
  ~HeartbeatResponder() = default;

  /// The resolved endpoint, e.g. "tcp://127.0.0.1:40124" (hello_ok.heartbeat_endpoint).
  [[nodiscard]] const std::string& endpoint() const noexcept { return endpoint_; }

 private:
  std::string endpoint_;
  std::jthread thread_;
};

}  // namespace dfc::protocol
