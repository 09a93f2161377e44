// The heartbeat (SPEC.md §9.1, protocol 1.6): where it binds and connects, a
// responder that answers while the main thread is busy, and a monitor that
// tells a silent server from a busy one, and (1.8) a stalled one, whose pongs
// come but whose progress stands still, from one that works.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "dfc/common/work_progress.hpp"
#include "dfc/protocol/client.hpp"
#include "dfc/protocol/heartbeat.hpp"
#include "dfc/protocol/heartbeat_monitor.hpp"
#include "dfc/protocol/heartbeat_responder.hpp"

namespace dfc::protocol {
namespace {

using namespace std::chrono_literals;

TEST(HeartbeatEndpoint, BindsBesideTheMainEndpoint) {
  EXPECT_EQ(heartbeat::bind_endpoint("tcp://127.0.0.1:40123"), "tcp://127.0.0.1:*");
  EXPECT_EQ(heartbeat::bind_endpoint("tcp://[::1]:40123"), "tcp://[::1]:*");
  EXPECT_EQ(heartbeat::bind_endpoint("ipc:///tmp/dfc/dem"), "ipc:///tmp/dfc/dem.heartbeat");
  EXPECT_EQ(heartbeat::bind_endpoint("inproc://dem"), "inproc://dem.heartbeat");
  EXPECT_EQ(heartbeat::bind_endpoint("udp://127.0.0.1:5"), std::nullopt);
  EXPECT_EQ(heartbeat::bind_endpoint("ipc://"), std::nullopt);
}

TEST(HeartbeatEndpoint, AWildcardHostIsReachedAtTheMainEndpointsHost) {
  EXPECT_EQ(heartbeat::connect_endpoint("tcp://0.0.0.0:5001", "tcp://10.1.2.3:5000"), "tcp://10.1.2.3:5001");
  EXPECT_EQ(heartbeat::connect_endpoint("tcp://127.0.0.1:5001", "tcp://127.0.0.1:5000"), "tcp://127.0.0.1:5001");
  EXPECT_EQ(heartbeat::connect_endpoint("ipc:///tmp/x.heartbeat", "ipc:///tmp/x"), "ipc:///tmp/x.heartbeat");
}

Message ping(Connection& connection) {
  Message request;
  request.type = std::string(type::ping);
  return connection.request_raw(std::move(request), 2s);
}

TEST(HeartbeatResponder, AnswersWhileTheMainThreadIsBusyAndCountsItsRequests) {
  zmq::context_t context(1);
  Liveness liveness;
  HeartbeatResponder responder(context, "inproc://busy_server.heartbeat", liveness, "1.6", std::nullopt);
  Connection connection(context, responder.endpoint(), "heartbeat");

  liveness.begin_request();  // the main thread is inside a long request
  std::this_thread::sleep_for(20ms);
  const Message busy = ping(connection);
  EXPECT_EQ(busy.type, "pong");
  EXPECT_EQ(busy.version, "1.6");
  EXPECT_EQ(busy.body["handled"], 0);
  ASSERT_TRUE(busy.body["busy_s"].is_number());
  EXPECT_GE(busy.body["busy_s"].get<double>(), 0.02);

  liveness.end_request(42);
  const Message idle = ping(connection);
  EXPECT_EQ(idle.body["handled"], 1);
  EXPECT_EQ(idle.body["step"], 42);
  EXPECT_TRUE(idle.body["busy_s"].is_null());
  // 1.8: the main thread's work counter, the process's.
  work_progress::advance();
  ASSERT_TRUE(idle.body["progress"].is_number_integer()) << idle.body;
  EXPECT_GT(ping(connection).body["progress"].get<std::int64_t>(), idle.body["progress"].get<std::int64_t>());

  Message other;
  other.type = std::string(type::advance);
  const Message refused = connection.request_raw(std::move(other), 2s);
  EXPECT_EQ(refused.type, "error");
  EXPECT_EQ(refused.body["code"], "UNKNOWN_TYPE");
}

TEST(HeartbeatResponder, StopsPromptlyWhenDestroyed) {
  zmq::context_t context(1);
  Liveness liveness;
  auto responder = std::make_unique<HeartbeatResponder>(context, "tcp://127.0.0.1:*", liveness, "1.6", std::nullopt);
  const auto start = std::chrono::steady_clock::now();
  responder.reset();
  EXPECT_LT(std::chrono::steady_clock::now() - start, 1s);
}

/// Polls `monitor` for `how_long` (as a client's wait does, every 10 ms) or
/// until it reports the server hung; returns what the last poll found.
Liveliness poll_for(HeartbeatMonitor& monitor, std::chrono::milliseconds how_long) {
  monitor.begin_wait();
  const auto until = std::chrono::steady_clock::now() + how_long;
  while (std::chrono::steady_clock::now() < until) {
    if (const Liveliness found = monitor.poll(); found != Liveliness::alive) return found;
    std::this_thread::sleep_for(10ms);
  }
  return Liveliness::alive;
}

/// A server's main thread that keeps working: it advances the work counter
/// every 20 ms until destroyed.
class ProgressingMainThread {
 public:
  ProgressingMainThread()
      : thread_([this] {
          while (working_.load()) {
            work_progress::advance();
            std::this_thread::sleep_for(20ms);
          }
        }) {}
  ~ProgressingMainThread() { working_ = false; }

 private:
  std::atomic<bool> working_{true};
  std::jthread thread_;
};

constexpr auto kNoStallRule = std::chrono::hours(1);

TEST(HeartbeatMonitor, ABusyServerThatAnswersIsAlive) {
  zmq::context_t context(1);
  Liveness liveness;
  HeartbeatResponder responder(context, "inproc://answering.heartbeat", liveness, "1.6", std::nullopt);
  liveness.begin_request();
  HeartbeatMonitor monitor(context, responder.endpoint(), {200ms, kNoStallRule}, std::nullopt);
  EXPECT_EQ(poll_for(monitor, 800ms), Liveliness::alive);  // four hang timeouts, busy all along
}

// A main thread that deadlocked: the heartbeat answers, the progress stands still.
TEST(HeartbeatMonitor, AServerWhoseProgressStandsStillIsStalledAfterTheStallTimeout) {
  zmq::context_t context(1);
  Liveness liveness;
  HeartbeatResponder responder(context, "inproc://stalled.heartbeat", liveness, "1.8", std::nullopt);
  liveness.begin_request();
  HeartbeatMonitor monitor(context, responder.endpoint(), {200ms, 400ms}, std::nullopt);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(poll_for(monitor, 3s), Liveliness::stalled);
  const auto waited = std::chrono::steady_clock::now() - start;
  EXPECT_GE(waited, 400ms);
  EXPECT_LT(waited, 1500ms);  // the stall is counted from the first pong, one ping interval (50 ms) into the wait
  const std::string description = monitor.stall_description();
  EXPECT_NE(description.find("its heartbeat (inproc://stalled.heartbeat) answers, but its progress stood at "), std::string::npos) << description;
  EXPECT_NE(description.find("busy for"), std::string::npos) << description;
}

// A slow request whose main thread bumps the counter is never stalled, however long it takes.
TEST(HeartbeatMonitor, AServerWhoseProgressMovesIsNotStalled) {
  zmq::context_t context(1);
  Liveness liveness;
  HeartbeatResponder responder(context, "inproc://progressing.heartbeat", liveness, "1.8", std::nullopt);
  liveness.begin_request();
  const ProgressingMainThread main_thread;
  HeartbeatMonitor monitor(context, responder.endpoint(), {200ms, 200ms}, std::nullopt);
  EXPECT_EQ(poll_for(monitor, 1s), Liveliness::alive);  // five stall timeouts
}

// A server before 1.8 sends no progress: only the silence rule holds it.
TEST(HeartbeatMonitor, AServerWithoutProgressIsNeverStalled) {
  zmq::context_t context(1);
  Liveness liveness(false);
  HeartbeatResponder responder(context, "inproc://older.heartbeat", liveness, "1.7", std::nullopt);
  liveness.begin_request();
  HeartbeatMonitor monitor(context, responder.endpoint(), {200ms, 100ms}, std::nullopt);
  EXPECT_EQ(poll_for(monitor, 800ms), Liveliness::alive);
}

TEST(HeartbeatMonitor, AServerThatAnswersNoPingIsHungAfterTheTimeout) {
  zmq::context_t context(1);
  zmq::socket_t silent(context, zmq::socket_type::router);  // receives the pings, answers none
  silent.bind("inproc://silent.heartbeat");
  HeartbeatMonitor monitor(context, "inproc://silent.heartbeat", {200ms, 100ms}, std::nullopt);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(poll_for(monitor, 2s), Liveliness::silent);  // silent, not stalled: no pong says anything about progress
  const auto waited = std::chrono::steady_clock::now() - start;
  EXPECT_GE(waited, 200ms);
  EXPECT_LT(waited, 1s);
  EXPECT_NE(monitor.silence_description().find("no pong from its heartbeat (inproc://silent.heartbeat)"), std::string::npos)
      << monitor.silence_description();
}

// A batch system suspends a whole job (SIGSTOP to every process, then
// SIGCONT): the client did not poll while the server did not answer. The
// pause is no silence; a server that stays silent afterwards still is.
TEST(HeartbeatMonitor, APauseOfTheClientItselfIsNotSilence) {
  zmq::context_t context(1);
  Liveness liveness;
  HeartbeatResponder responder(context, "inproc://paused.heartbeat", liveness, "1.8", std::nullopt);
  liveness.begin_request();
  const ProgressingMainThread main_thread;
  HeartbeatMonitor monitor(context, responder.endpoint(), {200ms, 300ms}, std::nullopt);
  monitor.begin_wait();
  EXPECT_EQ(monitor.poll(), Liveliness::alive);
  std::this_thread::sleep_for(700ms);  // the client paused for more than both timeouts
  EXPECT_EQ(monitor.poll(), Liveliness::alive);
  const auto until = std::chrono::steady_clock::now() + 600ms;
  Liveliness found = Liveliness::alive;
  while (found == Liveliness::alive && std::chrono::steady_clock::now() < until) {
    found = monitor.poll();
    std::this_thread::sleep_for(10ms);
  }
  EXPECT_EQ(found, Liveliness::alive);  // answering and progressing after the pause

  zmq::socket_t silent(context, zmq::socket_type::router);  // answers nothing
  silent.bind("inproc://silent-after-pause.heartbeat");
  HeartbeatMonitor silent_monitor(context, "inproc://silent-after-pause.heartbeat", {200ms, kNoStallRule}, std::nullopt);
  silent_monitor.begin_wait();
  std::this_thread::sleep_for(500ms);
  EXPECT_EQ(silent_monitor.poll(), Liveliness::alive);  // the pause itself proves nothing
  const auto start = std::chrono::steady_clock::now();
  found = Liveliness::alive;
  while (found == Liveliness::alive && std::chrono::steady_clock::now() - start < 2s) {
    found = silent_monitor.poll();
    std::this_thread::sleep_for(10ms);
  }
  EXPECT_EQ(found, Liveliness::silent);  // but silence after it is counted again
  EXPECT_GE(std::chrono::steady_clock::now() - start, 150ms);
}

}  // namespace
}  // namespace dfc::protocol
