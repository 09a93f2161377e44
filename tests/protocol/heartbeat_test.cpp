// The heartbeat (SPEC.md §9.1, protocol 1.6): where it binds and connects, a
// responder that answers while the main thread is busy, and a monitor that
// tells a silent server from a busy one.
#include <gtest/gtest.h>

#include <thread>

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

/// Polls `monitor` for `how_long` (as a client's wait does, every 10 ms); false once it reports the server hung.
bool stays_alive(HeartbeatMonitor& monitor, std::chrono::milliseconds how_long) {
  monitor.begin_wait();
  const auto until = std::chrono::steady_clock::now() + how_long;
  while (std::chrono::steady_clock::now() < until) {
    if (!monitor.poll()) return false;
    std::this_thread::sleep_for(10ms);
  }
  return true;
}

TEST(HeartbeatMonitor, ABusyServerThatAnswersIsAlive) {
  zmq::context_t context(1);
  Liveness liveness;
  HeartbeatResponder responder(context, "inproc://answering.heartbeat", liveness, "1.6", std::nullopt);
  liveness.begin_request();
  HeartbeatMonitor monitor(context, responder.endpoint(), 200ms, std::nullopt);
  EXPECT_TRUE(stays_alive(monitor, 800ms));  // four hang timeouts, busy all along
}

TEST(HeartbeatMonitor, AServerThatAnswersNoPingIsHungAfterTheTimeout) {
  zmq::context_t context(1);
  zmq::socket_t silent(context, zmq::socket_type::router);  // receives the pings, answers none
  silent.bind("inproc://silent.heartbeat");
  HeartbeatMonitor monitor(context, "inproc://silent.heartbeat", 200ms, std::nullopt);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(stays_alive(monitor, 2s));
  const auto waited = std::chrono::steady_clock::now() - start;
  EXPECT_GE(waited, 200ms);
  EXPECT_LT(waited, 1s);
  EXPECT_NE(monitor.silence_description().find("no pong from its heartbeat (inproc://silent.heartbeat)"), std::string::npos)
      << monitor.silence_description();
}

}  // namespace
}  // namespace dfc::protocol
