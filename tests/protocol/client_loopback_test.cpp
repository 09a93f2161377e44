// Connection and SolverClient over a real ROUTER/DEALER pair on loopback:
// deadlines, stale-reply skipping, error replies, the wait hook, raw frames,
// and the typed lifecycle against a ServerSession.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "dfc/common/version.hpp"
#include "dfc/protocol/client.hpp"
#include "dfc/protocol/server_session.hpp"
#include "loopback_router.hpp"
#include "scripted_backend.hpp"

namespace dfc::protocol::testing {
namespace {

using namespace std::chrono_literals;

Message request_of(std::string_view type) {
  Message message;
  message.type = std::string(type);
  return message;
}

class ClientLoopbackTest : public ::testing::Test {
 protected:
  zmq::context_t context{1};
  LoopbackRouter router{context};
  Connection connection{context, router.endpoint(), "test server"};
};

TEST_F(ClientLoopbackTest, EndpointIsLoopbackWithAConcretePort) {
  EXPECT_TRUE(router.endpoint().starts_with("tcp://127.0.0.1:")) << router.endpoint();
  EXPECT_EQ(router.endpoint().find('*'), std::string::npos) << router.endpoint();
}

TEST_F(ClientLoopbackTest, RequestReturnsTheMatchingReplyAndSeqsIncrease) {
  std::vector<std::int64_t> seqs;
  std::jthread server([&] {
    for (int i = 0; i < 2; ++i) {
      const auto request = router.receive();
      if (!request) return;
      const Message message = request->decoded();
      seqs.push_back(message.seq);
      router.reply(*request, LoopbackRouter::answer(message, "pong"));
    }
  });
  EXPECT_EQ(connection.request(request_of("ping"), 5s).type, "pong");
  EXPECT_EQ(connection.request(request_of("ping"), 5s).type, "pong");
  server.join();
  ASSERT_EQ(seqs.size(), 2u);
  EXPECT_LT(seqs[0], seqs[1]);
}

TEST_F(ClientLoopbackTest, NoReplyIsATimeoutErrorNamingTheServerWithinTheDeadline) {
  const auto started = std::chrono::steady_clock::now();
  try {
    (void)connection.request(request_of("advance"), 300ms);
    FAIL() << "no TimeoutError";
  } catch (const TimeoutError& e) {
    EXPECT_NE(std::string(e.what()).find("test server"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("advance"), std::string::npos) << e.what();
  }
  const auto elapsed = std::chrono::steady_clock::now() - started;
  EXPECT_GE(elapsed, 290ms);  // the wait is sliced in whole milliseconds
  EXPECT_LT(elapsed, 1500ms);
}

// A pause of the client itself (the job suspended and continued) longer than
// the deadline does not count against the server: it answers 300 ms after the
// pause and is still in time for a 1.5 s deadline. Without the pause rule the
// 2 s pause alone ran out the deadline (seen: a suspended study run stopped
// as "hung" when it was continued).
TEST_F(ClientLoopbackTest, APauseOfTheClientItselfDoesNotRunOutTheDeadline) {
  std::atomic<bool> paused = false;
  connection.set_wait_hook([&] {
    if (!paused.exchange(true)) std::this_thread::sleep_for(2s);  // the client stopped once
  });
  std::jthread server([&] {
    const auto request = router.receive();
    if (!request) return;
    while (!paused) std::this_thread::sleep_for(10ms);
    std::this_thread::sleep_for(2300ms);  // 300 ms after the client's pause ended
    router.reply(*request, LoopbackRouter::answer(request->decoded(), "pong"));
  });
  EXPECT_EQ(connection.request(request_of("ping"), 1500ms).type, "pong");
}

TEST_F(ClientLoopbackTest, LateReplyToAnAbandonedRequestIsSkipped) {
  std::jthread server([&] {
    const auto abandoned = router.receive();
    const auto current = router.receive();  // arrives after the client gave up on the first
    if (!abandoned || !current) return;
    Message stale = LoopbackRouter::answer(abandoned->decoded(), "pong");
    stale.body = {{"which", "stale"}};
    Message fresh = LoopbackRouter::answer(current->decoded(), "pong");
    fresh.body = {{"which", "fresh"}};
    router.reply(*abandoned, stale);
    router.reply(*current, fresh);
  });
  EXPECT_THROW((void)connection.request(request_of("ping"), 200ms), TimeoutError);
  const Message reply = connection.request(request_of("ping"), 5s);
  EXPECT_EQ(reply.body.value("which", ""), "fresh");
}

TEST_F(ClientLoopbackTest, AReplyWithAWrongReplyToIsNamedInTheTimeout) {
  // A server that answers with the wrong reply_to looks like one that never
  // answers; the timeout says what did arrive (SPEC.md §3.1).
  std::jthread server([&] {
    const auto request = router.receive();
    if (!request) return;
    Message wrong = LoopbackRouter::answer(request->decoded(), "pong");
    wrong.reply_to = *wrong.reply_to + 40;
    router.reply(*request, wrong);
  });
  try {
    (void)connection.request(request_of("ping"), 300ms);
    FAIL() << "no TimeoutError";
  } catch (const TimeoutError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("reply_to 41"), std::string::npos) << what;
    EXPECT_NE(what.find("seq 1"), std::string::npos) << what;
  }
}

TEST_F(ClientLoopbackTest, ErrorReplyIsARemoteErrorWithCodeAndKeyOrReturnedRaw) {
  std::jthread server([&] {
    for (int i = 0; i < 2; ++i) {
      const auto request = router.receive();
      if (!request) return;
      router.reply(*request, make_error(request->decoded().seq, ErrorCode::bad_config, "contact.law: unknown", "contact.law"));
    }
  });
  try {
    (void)connection.request(request_of("configure"), 5s);
    FAIL() << "no RemoteError";
  } catch (const RemoteError& e) {
    EXPECT_EQ(e.code(), "BAD_CONFIG");
    EXPECT_EQ(e.key(), "contact.law");
    EXPECT_STREQ(e.what(), "contact.law: unknown");
  }
  const Message raw = connection.request_raw(request_of("configure"), 5s);
  EXPECT_EQ(raw.type, type::error);
  EXPECT_EQ(raw.body["code"], "BAD_CONFIG");
}

TEST_F(ClientLoopbackTest, WaitHookRunsWhileWaitingAndCanAbortTheWait) {
  int calls = 0;
  connection.set_wait_hook([&] {
    if (++calls == 3) throw std::runtime_error("server process exited");
  });
  const auto started = std::chrono::steady_clock::now();
  try {
    (void)connection.request(request_of("advance"), 10s);
    FAIL() << "the hook's exception did not end the wait";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "server process exited");
  }
  EXPECT_EQ(calls, 3);
  EXPECT_LT(std::chrono::steady_clock::now() - started, 2s);
}

TEST_F(ClientLoopbackTest, RawFramesArriveUnchangedAndAnyReplyIsReturned) {
  std::vector<std::string> received;
  std::jthread server([&] {
    const auto request = router.receive();
    if (!request) return;
    received = request->frames;
    router.reply(*request, make_error(std::nullopt, ErrorCode::bad_message, "frame 0 is not a JSON object"));
  });
  const auto reply = connection.send_frames_raw({"not json", std::string(3, '\0')}, 5s);
  server.join();
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->body["code"], "BAD_MESSAGE");
  EXPECT_FALSE(reply->reply_to.has_value());
  EXPECT_EQ(received, (std::vector<std::string>{"not json", std::string(3, '\0')}));
}

// SolverClient's typed calls against the real ServerSession, over TCP.
TEST(SolverClientLoopback, DrivesTheWholeLifecycleOfAServerSession) {
  zmq::context_t context{1};
  LoopbackRouter router{context};
  ScriptedBackend backend;
  std::jthread server([&] {
    ServerSession session(backend, Limits{});
    while (!session.closed()) {
      const auto request = router.receive();
      if (!request) return;
      router.reply(*request, session.handle(request->decoded()));
    }
  });
  SolverClient client(context, router.endpoint(), "scripted server");
  const auto hello = client.hello("test", 5s);
  EXPECT_EQ(hello.solver_name, "scripted");
  EXPECT_EQ(hello.role, "continuum");
  EXPECT_TRUE(hello.has(capability::provides_interface));
  EXPECT_FALSE(hello.has(capability::accepts_interface));
  const std::string section = R"({"side": 2})";
  const nlohmann::json configured = client.configure(section, 5s);
  EXPECT_EQ(configured["scenario_hash"], fnv1a64_hex(section));
  const InterfaceMesh mesh = client.get_interface(5s);
  EXPECT_EQ(mesh.node_ids, (std::vector<std::int64_t>{11, 12, 13}));
  EXPECT_EQ(mesh.facet_count(), 1);
  const Message advanced = client.advance(0, 2, 0.5, {}, 5s);
  EXPECT_EQ(advanced.step, 2);
  EXPECT_EQ(client.query(5s)["kinetic_energy_j"], 2.0);
  EXPECT_EQ(client.snapshot(5s).body["kind"], "grid");
  try {
    (void)client.advance(0, 1, 0.5, {}, 5s);
    FAIL() << "advance from a stale step was accepted";
  } catch (const RemoteError& e) {
    EXPECT_EQ(e.code(), "STEP_MISMATCH");
  }
  client.shutdown(5s);
  server.join();
  EXPECT_EQ(backend.advances.size(), 1u);
}

}  // namespace
}  // namespace dfc::protocol::testing
