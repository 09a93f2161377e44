// ServerSession, driven message by message: every transition of SPEC.md
// §5.1, step semantics (§5.2), and how backend failures become error replies.
#include <gtest/gtest.h>

#include "dfc/common/unstable_step_error.hpp"
#include "dfc/common/version.hpp"
#include "dfc/protocol/server_session.hpp"
#include "scripted_backend.hpp"

namespace dfc::protocol::testing {
namespace {

class ServerSessionTest : public ::testing::Test {
 protected:
  ScriptedBackend backend;
  ServerSession session{backend, Limits{}};
  std::int64_t seq = 0;

  Message send(std::string_view type, nlohmann::json body = nlohmann::json::object(), std::optional<std::int64_t> step = std::nullopt,
               std::vector<Array> arrays = {}, std::string version = version_string()) {
    Message request;
    request.type = std::string(type);
    request.version = std::move(version);
    request.seq = ++seq;
    request.step = step;
    request.body = std::move(body);
    request.arrays = std::move(arrays);
    Message reply = session.handle(request);
    EXPECT_EQ(reply.reply_to, request.seq) << "every reply answers its request's seq";
    return reply;
  }
  Message hello() { return send(type::hello, {{"client", {{"name", "test"}, {"version", "0"}}}}); }
  Message configure(const std::string& text = R"({"a": 1})") { return send(type::configure, {{"section_json", text}}); }
  Message advance(std::int64_t step, nlohmann::json n_steps = 1, nlohmann::json dt = 0.25) {
    return send(type::advance, {{"n_steps", n_steps}, {"dt", dt}}, step);
  }
  void reach_configured() {
    ASSERT_EQ(hello().type, type::hello_ok);
    ASSERT_EQ(configure().type, type::configured);
  }
  void reach_running() {
    reach_configured();
    ASSERT_EQ(advance(0).type, type::advanced);
  }
  void reach_failed() {
    reach_running();
    backend.on_advance = [](const AdvanceRequest&) { throw SolverError("velocity became NaN at node 3"); };
    ASSERT_EQ(error_code(advance(1)), "SOLVER_FAILURE");
    backend.on_advance = nullptr;
  }
  static std::string error_code(const Message& reply) {
    return reply.type == type::error ? reply.body.value("code", "(none)") : "(not an error: " + reply.type + ")";
  }
};

TEST_F(ServerSessionTest, StartsFreshAndAnswersPing) {
  EXPECT_EQ(session.state(), SessionState::fresh);
  EXPECT_EQ(send(type::ping).type, type::pong);
  EXPECT_EQ(session.state(), SessionState::fresh);
}

TEST_F(ServerSessionTest, EverythingButHelloPingShutdownIsOutOfOrderWhenFresh) {
  for (const auto t : {type::configure, type::get_interface, type::set_interface, type::advance, type::query, type::snapshot}) {
    EXPECT_EQ(error_code(send(t)), "OUT_OF_ORDER") << t;
    EXPECT_EQ(session.state(), SessionState::fresh) << t;
  }
}

TEST_F(ServerSessionTest, HelloGreetsWithIdentityCapabilitiesAndLimits) {
  const Message reply = hello();
  ASSERT_EQ(reply.type, type::hello_ok);
  EXPECT_EQ(session.state(), SessionState::greeted);
  EXPECT_EQ(reply.body["protocol_version"], version_string());
  EXPECT_EQ(reply.body["solver"]["name"], "scripted");
  EXPECT_EQ(reply.body["solver"]["version"], "9.9.9");
  EXPECT_EQ(reply.body["role"], "continuum");
  EXPECT_EQ(reply.body["capabilities"], nlohmann::json({"provides_interface", "snapshot"}));
  EXPECT_EQ(reply.body["limits"]["max_header_bytes"], Limits{}.max_header_bytes);
  EXPECT_EQ(reply.body["limits"]["max_array_bytes"], Limits{}.max_array_bytes);
  EXPECT_EQ(reply.body["limits"]["max_arrays"], Limits{}.max_arrays);
  EXPECT_EQ(error_code(hello()), "OUT_OF_ORDER") << "hello is allowed only once";
}

TEST_F(ServerSessionTest, OtherMajorVersionIsRefusedNamingBothAndStaysFresh) {
  const Message reply = send(type::hello, nlohmann::json::object(), std::nullopt, {}, "2.0");
  EXPECT_EQ(error_code(reply), "VERSION_MISMATCH");
  const std::string message = reply.body["message"];
  EXPECT_NE(message.find("2.0"), std::string::npos) << message;
  EXPECT_NE(message.find(version_string()), std::string::npos) << message;
  EXPECT_EQ(session.state(), SessionState::fresh);
  EXPECT_EQ(hello().type, type::hello_ok);
}

TEST_F(ServerSessionTest, OtherMinorVersionIsAccepted) {
  EXPECT_EQ(send(type::hello, nlohmann::json::object(), std::nullopt, {}, std::to_string(kVersionMajor) + ".99").type, type::hello_ok);
}

TEST_F(ServerSessionTest, UnknownTypeIsUnknownTypeInAnyState) {
  EXPECT_EQ(error_code(send("teleport")), "UNKNOWN_TYPE");
  reach_configured();
  EXPECT_EQ(error_code(send("teleport")), "UNKNOWN_TYPE");
  EXPECT_EQ(session.state(), SessionState::configured);
}

// SPEC.md §1: checkpoint and restore came with 1.3; a session playing an
// older server knows neither, as that server did.
TEST_F(ServerSessionTest, CheckpointAndRestoreAreUnknownTypesBeforeMinor3) {
  reach_configured();
  session.declare_minor(2);
  EXPECT_EQ(error_code(send(type::checkpoint, {{"path", "x.checkpoint"}})), "UNKNOWN_TYPE");
  EXPECT_EQ(error_code(send(type::restore, {{"path", "x.checkpoint"}})), "UNKNOWN_TYPE");
  session.declare_minor(3);
  EXPECT_EQ(error_code(send(type::checkpoint, {{"path", "x.checkpoint"}})), "UNSUPPORTED");
}

TEST_F(ServerSessionTest, AnUnknownType200kBLongIsEchoedCutWithItsLength) {
  // Issue 42: the reply's message quotes the type, but not all of it.
  const Message reply = send(std::string(200'000, 't'));
  EXPECT_EQ(error_code(reply), "UNKNOWN_TYPE");
  const std::string message = reply.body.value("message", "");
  EXPECT_LT(message.size(), 300u) << message.substr(0, 300);
  EXPECT_NE(message.find("(200000 bytes)"), std::string::npos) << message.substr(0, 300);
}

TEST_F(ServerSessionTest, GreetedRefusesAdvanceQueryAndInterface) {
  ASSERT_EQ(hello().type, type::hello_ok);
  for (const auto t : {type::get_interface, type::set_interface, type::query, type::snapshot}) EXPECT_EQ(error_code(send(t)), "OUT_OF_ORDER") << t;
  EXPECT_EQ(error_code(advance(0)), "OUT_OF_ORDER");
  EXPECT_EQ(session.state(), SessionState::greeted);
  EXPECT_TRUE(backend.advances.empty());
}

TEST_F(ServerSessionTest, ConfigureHashesTheExactTextAndPassesTheParsedSection) {
  ASSERT_EQ(hello().type, type::hello_ok);
  const std::string text = "{ \"mesh\": {\"cells\": 4} }\n";
  const Message reply = configure(text);
  ASSERT_EQ(reply.type, type::configured);
  EXPECT_EQ(reply.body["scenario_hash"], fnv1a64_hex(text));
  EXPECT_EQ(reply.body["info"]["dt_suggested"], 0.5);
  EXPECT_TRUE(reply.body["info"]["dt_max"].is_null());
  EXPECT_EQ(backend.configured_section, (nlohmann::json{{"mesh", {{"cells", 4}}}}));
  EXPECT_EQ(session.state(), SessionState::configured);
  EXPECT_EQ(error_code(configure()), "OUT_OF_ORDER") << "configure is allowed only once";
}

TEST_F(ServerSessionTest, InvalidJsonOrNonObjectSectionIsBadConfigAndStaysGreeted) {
  ASSERT_EQ(hello().type, type::hello_ok);
  EXPECT_EQ(error_code(configure("{\"a\": ")), "BAD_CONFIG");
  EXPECT_EQ(error_code(configure("[1, 2]")), "BAD_CONFIG");
  EXPECT_EQ(session.state(), SessionState::greeted);
  EXPECT_FALSE(backend.configured_section.has_value());
}

TEST_F(ServerSessionTest, MissingSectionTextIsBadMessage) {
  ASSERT_EQ(hello().type, type::hello_ok);
  EXPECT_EQ(error_code(send(type::configure)), "BAD_MESSAGE");
  EXPECT_EQ(error_code(send(type::configure, {{"section_json", nlohmann::json::object()}})), "BAD_MESSAGE");
  EXPECT_EQ(session.state(), SessionState::greeted);
}

TEST_F(ServerSessionTest, ConfigErrorIsBadConfigWithKeyAndACorrectedSectionIsAccepted) {
  ASSERT_EQ(hello().type, type::hello_ok);
  backend.on_configure = [](const nlohmann::json& section) {
    if (section.contains("contact")) throw ConfigError("contact.law", "unknown law 'sticky'; known: linear, hertz");
  };
  const Message refused = configure(R"({"contact": {"law": "sticky"}})");
  EXPECT_EQ(error_code(refused), "BAD_CONFIG");
  EXPECT_EQ(refused.body["key"], "contact.law");
  EXPECT_NE(refused.body["message"].get<std::string>().find("sticky"), std::string::npos);
  EXPECT_EQ(session.state(), SessionState::greeted);
  EXPECT_EQ(configure(R"({"other": 1})").type, type::configured);
}

TEST_F(ServerSessionTest, GetInterfaceSendsTheBackendMesh) {
  reach_configured();
  const Message reply = send(type::get_interface);
  ASSERT_EQ(reply.type, type::interface);
  ASSERT_NE(find_array(reply.arrays, field::node_ids), nullptr);
  EXPECT_EQ(find_array(reply.arrays, field::node_ids)->to_i64(), (std::vector<std::int64_t>{11, 12, 13}));
  EXPECT_EQ(find_array(reply.arrays, field::coordinates)->shape, (std::vector<std::int64_t>{3, 3}));
  EXPECT_EQ(find_array(reply.arrays, field::facets)->shape, (std::vector<std::int64_t>{1, 3}));
}

TEST_F(ServerSessionTest, GetInterfaceWithoutTheCapabilityIsUnsupported) {
  struct NoInterface final : SolverBackend {
    SolverIdentity identity() const override { return {"plain", "1", "dem", {}}; }
    nlohmann::json configure(const nlohmann::json&) override { return {{"dt_suggested", 1.0}, {"dt_max", 1.0}}; }
    AdvanceResult advance(const AdvanceRequest&) override { return {}; }
    nlohmann::json monitors() override { return nlohmann::json::object(); }
    std::vector<Array> snapshot(std::string&) override { return {}; }
  } plain;
  ServerSession plain_session(plain, Limits{});
  const auto request = [&](std::string_view t, nlohmann::json body = nlohmann::json::object()) {
    Message m;
    m.type = std::string(t);
    m.body = std::move(body);
    return plain_session.handle(m);
  };
  ASSERT_EQ(request(type::hello).type, type::hello_ok);
  ASSERT_EQ(request(type::configure, {{"section_json", "{}"}}).type, type::configured);
  EXPECT_EQ(request(type::get_interface).body["code"], "UNSUPPORTED");
  EXPECT_EQ(request(type::set_interface).body["code"], "BAD_ARRAY") << "a set_interface without arrays is refused before the capability";
  EXPECT_EQ(plain_session.state(), SessionState::configured);
}

std::vector<Array> mesh_arrays(std::vector<std::int64_t> facets) {
  return {Array::from_i64(field::node_ids, {3}, std::vector<std::int64_t>{7, 8, 9}),
          Array::from_f64(field::coordinates, {3, 3}, std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0}),
          Array::from_i64(field::facets, {std::int64_t(facets.size() / 3), 3}, facets)};
}

TEST_F(ServerSessionTest, SetInterfaceHandsTheMeshToTheBackend) {
  reach_configured();
  EXPECT_EQ(send(type::set_interface, nlohmann::json::object(), std::nullopt, mesh_arrays({0, 1, 2})).type, type::ok);
  ASSERT_TRUE(backend.received_mesh.has_value());
  EXPECT_EQ(backend.received_mesh->node_ids, (std::vector<std::int64_t>{7, 8, 9}));
  EXPECT_EQ(backend.received_mesh->facets, (std::vector<std::int64_t>{0, 1, 2}));
}

TEST_F(ServerSessionTest, SetInterfaceWithAFacetOutOfRangeIsBadArray) {
  reach_configured();
  EXPECT_EQ(error_code(send(type::set_interface, nlohmann::json::object(), std::nullopt, mesh_arrays({0, 1, 3}))), "BAD_ARRAY");
  EXPECT_FALSE(backend.received_mesh.has_value());
}

TEST_F(ServerSessionTest, SetInterfaceWithADuplicateNodeIdIsBadArrayNamingIt) {
  reach_configured();
  std::vector<Array> arrays = mesh_arrays({0, 1, 2});
  arrays[0] = Array::from_i64(field::node_ids, {3}, std::vector<std::int64_t>{7, 8, 7});
  const Message reply = send(type::set_interface, nlohmann::json::object(), std::nullopt, arrays);
  EXPECT_EQ(error_code(reply), "BAD_ARRAY");
  EXPECT_NE(reply.body["message"].get<std::string>().find("id 7"), std::string::npos) << reply.body.dump();
  EXPECT_FALSE(backend.received_mesh.has_value());
  EXPECT_EQ(session.state(), SessionState::configured);
}

TEST_F(ServerSessionTest, AdvanceCountsStepsAndPassesTheRequest) {
  reach_configured();
  const std::vector<Array> inputs{Array::from_f64(field::force, {1, 3}, std::vector<double>{4, 5, 6})};
  const Message first = send(type::advance, {{"n_steps", 3}, {"dt", 0.125}}, 0, inputs);
  ASSERT_EQ(first.type, type::advanced);
  EXPECT_EQ(first.step, 3);
  EXPECT_EQ(first.body["monitors"]["kinetic_energy_j"], 1.0);
  ASSERT_NE(find_array(first.arrays, field::velocity), nullptr);
  EXPECT_EQ(session.state(), SessionState::running);
  ASSERT_EQ(backend.advances.size(), 1u);
  EXPECT_EQ(backend.advances[0].first_step, 0);
  EXPECT_EQ(backend.advances[0].n_steps, 3);
  EXPECT_EQ(backend.advances[0].dt, 0.125);
  EXPECT_EQ(backend.advances[0].inputs[0].to_f64(), (std::vector<double>{4, 5, 6}));

  const Message second = advance(3, 2, 0.5);  // dt may change between advances
  EXPECT_EQ(second.step, 5);
  EXPECT_EQ(backend.advances.at(1).first_step, 3);
  EXPECT_EQ(session.step(), 5);
}

TEST_F(ServerSessionTest, StepMismatchRunsNothingAndLeavesTheStep) {
  reach_running();
  const Message reply = advance(7);
  EXPECT_EQ(error_code(reply), "STEP_MISMATCH");
  EXPECT_NE(reply.body["message"].get<std::string>().find("7"), std::string::npos);
  EXPECT_EQ(session.step(), 1);
  EXPECT_EQ(backend.advances.size(), 1u);
  EXPECT_EQ(send(type::query).step, 1);
}

TEST_F(ServerSessionTest, MalformedAdvanceIsBadMessageAndLeavesTheStep) {
  reach_configured();
  EXPECT_EQ(error_code(send(type::advance, {{"n_steps", 1}, {"dt", 0.1}})), "BAD_MESSAGE") << "no header step";
  EXPECT_EQ(error_code(advance(0, 0)), "BAD_MESSAGE");
  EXPECT_EQ(error_code(advance(0, -1)), "BAD_MESSAGE");
  EXPECT_EQ(error_code(advance(0, 1'000'000'001)), "BAD_MESSAGE");
  EXPECT_EQ(error_code(advance(0, 1.5)), "BAD_MESSAGE");
  EXPECT_EQ(error_code(advance(0, 1, 0.0)), "BAD_MESSAGE");
  EXPECT_EQ(error_code(advance(0, 1, -0.1)), "BAD_MESSAGE");
  EXPECT_EQ(error_code(advance(0, 1, "fast")), "BAD_MESSAGE");
  EXPECT_EQ(error_code(send(type::advance, {{"n_steps", 1}}, 0)), "BAD_MESSAGE") << "no dt";
  EXPECT_EQ(session.step(), 0);
  EXPECT_EQ(session.state(), SessionState::configured);
  EXPECT_TRUE(backend.advances.empty());
}

TEST_F(ServerSessionTest, BackendBadArrayLeavesStepAndState) {
  reach_running();
  backend.on_advance = [](const AdvanceRequest& request) { (void)require_f64(request.inputs, field::force, 1, 3); };
  const Message reply = advance(1);
  EXPECT_EQ(error_code(reply), "BAD_ARRAY");
  EXPECT_NE(reply.body["message"].get<std::string>().find("force"), std::string::npos);
  EXPECT_EQ(session.step(), 1);
  EXPECT_EQ(session.state(), SessionState::running);
}

TEST_F(ServerSessionTest, UnexpectedExceptionIsInternalAndLeavesStepAndState) {
  reach_running();
  backend.on_advance = [](const AdvanceRequest&) { throw std::runtime_error("index out of range"); };
  EXPECT_EQ(error_code(advance(1)), "INTERNAL");
  EXPECT_EQ(session.step(), 1);
  EXPECT_EQ(session.state(), SessionState::running);
}

TEST_F(ServerSessionTest, SolverErrorFailsTheSessionAndRefusesFurtherAdvances) {
  reach_failed();
  EXPECT_EQ(session.state(), SessionState::failed);
  EXPECT_EQ(session.step(), 1);
  EXPECT_EQ(error_code(advance(1)), "OUT_OF_ORDER");
  EXPECT_EQ(send(type::query).type, type::monitors);
  EXPECT_EQ(send(type::snapshot).type, type::snapshot_data);
  EXPECT_EQ(send(type::ping).type, type::pong);
  EXPECT_EQ(session.state(), SessionState::failed);
}

TEST_F(ServerSessionTest, AnUnstableStepIsRefusedWithDtMaxAndChangesNothing) {
  // SPEC.md §5.2: a step above the stability limit is refused before anything
  // runs; the reply says the largest stable step as a number, and the client
  // may go on with it (unlike every other SOLVER_FAILURE, which is fatal).
  reach_running();
  backend.on_advance = [](const AdvanceRequest& request) {
    if (request.dt > 0.3) throw UnstableStepError("dt exceeds the critical step 0.3 s", 0.3);
  };
  const Message refused = advance(1, 1, 0.5);
  EXPECT_EQ(error_code(refused), "SOLVER_FAILURE");
  ASSERT_TRUE(refused.body.contains("dt_max")) << refused.body.dump();
  EXPECT_EQ(refused.body["dt_max"], 0.3);
  EXPECT_EQ(session.state(), SessionState::running);
  EXPECT_EQ(session.step(), 1);
  const Message retried = advance(1, 1, 0.3);
  EXPECT_EQ(retried.type, type::advanced);
  EXPECT_EQ(retried.step, 2);
}

TEST_F(ServerSessionTest, OtherSolverFailuresCarryNoDtMaxAndAreFatal) {
  reach_running();
  backend.on_advance = [](const AdvanceRequest&) { throw SolverError("a particle position became non-finite"); };
  const Message reply = advance(1);
  EXPECT_EQ(error_code(reply), "SOLVER_FAILURE");
  EXPECT_FALSE(reply.body.contains("dt_max"));
  EXPECT_EQ(session.state(), SessionState::failed);
}

TEST_F(ServerSessionTest, RunningRefusesInterfaceExchangeAndConfigure) {
  reach_running();
  EXPECT_EQ(error_code(send(type::get_interface)), "OUT_OF_ORDER");
  EXPECT_EQ(error_code(send(type::set_interface, nlohmann::json::object(), std::nullopt, mesh_arrays({0, 1, 2}))), "OUT_OF_ORDER");
  EXPECT_EQ(error_code(configure()), "OUT_OF_ORDER");
  EXPECT_EQ(error_code(hello()), "OUT_OF_ORDER");
  EXPECT_FALSE(backend.received_mesh.has_value());
}

TEST_F(ServerSessionTest, QueryAndSnapshotReportTheCurrentStep) {
  reach_configured();
  EXPECT_EQ(send(type::query).step, 0);
  ASSERT_EQ(advance(0, 4).type, type::advanced);
  const Message monitors = send(type::query);
  EXPECT_EQ(monitors.type, type::monitors);
  EXPECT_EQ(monitors.step, 4);
  EXPECT_EQ(monitors.body["monitors"]["kinetic_energy_j"], 2.0);
  const Message snapshot = send(type::snapshot);
  EXPECT_EQ(snapshot.type, type::snapshot_data);
  EXPECT_EQ(snapshot.step, 4);
  EXPECT_EQ(snapshot.body["kind"], "grid");
  EXPECT_EQ(snapshot.arrays.size(), 1u);
}

TEST(ServerSessionShutdown, ClosesFromEveryState) {
  const std::vector<SessionState> states{SessionState::fresh, SessionState::greeted, SessionState::configured, SessionState::running,
                                         SessionState::failed};
  for (std::size_t reached = 0; reached < states.size(); ++reached) {
    // A new session per starting state, walked there one request at a time.
    ScriptedBackend backend;
    ServerSession session(backend, Limits{});
    std::int64_t seq = 0;
    const auto send = [&](std::string_view t, nlohmann::json body = nlohmann::json::object(), std::optional<std::int64_t> step = std::nullopt) {
      Message request;
      request.type = std::string(t);
      request.seq = ++seq;
      request.step = step;
      request.body = std::move(body);
      return session.handle(request);
    };
    if (reached >= 1) (void)send(type::hello);
    if (reached >= 2) (void)send(type::configure, {{"section_json", "{}"}});
    if (reached >= 3) (void)send(type::advance, {{"n_steps", 1}, {"dt", 0.1}}, 0);
    if (reached >= 4) {
      backend.on_advance = [](const AdvanceRequest&) { throw SolverError("diverged"); };
      (void)send(type::advance, {{"n_steps", 1}, {"dt", 0.1}}, 1);
    }
    ASSERT_EQ(session.state(), states[reached]) << "setup reached " << session_state_name(session.state());
    EXPECT_EQ(send(type::shutdown).type, type::bye) << "from " << session_state_name(states[reached]);
    EXPECT_TRUE(session.closed()) << "from " << session_state_name(states[reached]);
  }
}

TEST_F(ServerSessionTest, ReplySeqsIncreaseByOneAcrossRepliesAndErrors) {
  // SPEC.md §3.1: a server numbers its replies 0, 1, 2, ... in the order it
  // sends them, whatever they answer, including messages it could not decode.
  const Message a = send(type::ping);
  const Message b = send("teleport");
  const Message c = session.refuse_undecodable(DecodeError(ErrorCode::bad_message, "frame 0 is not a JSON object", std::nullopt));
  const Message d = session.refuse_undecodable(DecodeError(ErrorCode::bad_message, "header field 'protocol' must be \"dfc\"", 41));
  const Message e = send(type::ping);
  EXPECT_EQ(a.seq, 0);
  EXPECT_EQ(b.seq, 1);
  EXPECT_EQ(c.seq, 2);
  EXPECT_EQ(d.seq, 3);
  EXPECT_EQ(e.seq, 4);
  EXPECT_FALSE(c.reply_to.has_value()) << "no seq could be read, so there is nothing to answer";
  EXPECT_EQ(d.reply_to, 41) << "the seq was read before the failure";
  EXPECT_EQ(d.body["code"], "BAD_MESSAGE");
}

}  // namespace
}  // namespace dfc::protocol::testing
