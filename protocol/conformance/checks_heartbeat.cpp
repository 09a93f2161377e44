// SPEC.md §9.1 (1.6): hello_ok announces a heartbeat endpoint beside the main
// one; it answers ping with pong, whose body counts the requests the main
// socket has answered, and refuses every other type. For servers that
// declare 1.6 or later (Check::since_minor); older ones are skipped. From
// 1.8 every pong carries `progress`, the main thread's work counter, which
// never decreases (heartbeat.progress; skipped for a server declaring 1.7 or older).
#include "announced_heartbeat.hpp"
#include "check.hpp"
#include "context.hpp"
#include "dfc/protocol/heartbeat.hpp"
#include "dfc/protocol/transport.hpp"
#include "expectations.hpp"

namespace dfc::conformance {

namespace protocol = dfc::protocol;
namespace heartbeat = dfc::protocol::heartbeat;

namespace {

constexpr std::string_view kLoopbackPrefix = "tcp://127.0.0.1:";

}  // namespace

std::string announced_endpoint(const Context& context) {
  const nlohmann::json& body = context.hello_reply->body;
  const auto it = body.find(heartbeat::endpoint_key);
  expect(it != body.end() && it->is_string() && !it->get<std::string>().empty(),
         "hello_ok of a " + body.value("protocol_version", std::string("?")) + " server needs a non-empty string '" +
             std::string(heartbeat::endpoint_key) + "' (SPEC.md §9.1)");
  const std::string endpoint = it->get<std::string>();
  if (const auto problem = protocol::endpoint_problem(endpoint)) throw CheckFailure("hello_ok.heartbeat_endpoint: " + *problem);
  // Bound beside the main socket, which was told to listen on the loopback only.
  expect(!endpoint.starts_with("tcp://") || endpoint.starts_with(kLoopbackPrefix),
         "hello_ok.heartbeat_endpoint '" + endpoint + "' is not on the loopback interface the server was told to bind (tcp://127.0.0.1:*)");
  return endpoint;
}

namespace {

protocol::Message ping_heartbeat(Context& context, protocol::Connection& connection, std::string_view type = protocol::type::ping) {
  protocol::Message request;
  request.type = std::string(type);
  try {
    return connection.request_raw(std::move(request), context.timeout());
  } catch (const protocol::TimeoutError& e) {
    // The main socket still answers (the runner pings it after each check): only the heartbeat is silent.
    throw CheckFailure(std::string("the heartbeat did not answer: ") + e.what());
  }
}

std::int64_t handled_in(const protocol::Message& pong) {
  const auto it = pong.body.find(heartbeat::handled_key);
  expect(it != pong.body.end() && it->is_number_integer() && it->get<std::int64_t>() >= 0,
         "the heartbeat's pong needs body.handled, an integer >= 0 (requests the main socket answered), got " + pong.body.dump());
  return it->get<std::int64_t>();
}

void heartbeat_is_announced(Context& context) { (void)announced_endpoint(context); }

void heartbeat_answers_ping(Context& context) {
  protocol::Connection connection(context.zmq_context(), announced_endpoint(context), "the heartbeat", protocol::Limits{}, context.server_key());
  const protocol::Message first = ping_heartbeat(context, connection);
  expect_type(first, protocol::type::pong);
  const std::int64_t before = handled_in(first);
  expect(before >= 1, "the heartbeat's pong says " + std::to_string(before) + " requests handled, but hello was answered before it");
  const auto step = first.body.find(heartbeat::step_key);
  expect(step != first.body.end() && step->is_number_integer() && step->get<std::int64_t>() >= 0,
         "the heartbeat's pong needs body.step, an integer >= 0, got " + first.body.dump());
  const auto busy = first.body.find(heartbeat::busy_key);
  expect(busy != first.body.end() && (busy->is_null() || busy->is_number()),
         "the heartbeat's pong needs body.busy_s, a number or null, got " + first.body.dump());
  // The count follows the main socket: one more request answered there, one more in the next pong.
  context.expect_alive();
  const std::int64_t after = handled_in(ping_heartbeat(context, connection));
  expect(after > before, "the heartbeat's pong still says " + std::to_string(after) + " requests handled after one more was answered");
}

std::int64_t progress_in(const protocol::Message& pong) {
  const auto it = pong.body.find(heartbeat::progress_key);
  expect(it != pong.body.end() && it->is_number_integer() && it->get<std::int64_t>() >= 0,
         "the pong of a 1." + std::to_string(heartbeat::kProgressSinceMinor) +
             " server needs body.progress, an integer >= 0 (the work its main thread has done, SPEC.md §9.1), got " + pong.body.dump());
  return it->get<std::int64_t>();
}

void heartbeat_reports_progress(Context& context) {
  protocol::Connection connection(context.zmq_context(), announced_endpoint(context), "the heartbeat", protocol::Limits{}, context.server_key());
  std::int64_t before = progress_in(ping_heartbeat(context, connection));
  // Around requests of the main socket and back to back: the counter never goes back.
  for (int round = 0; round < 3; ++round) {
    context.expect_alive();
    const std::int64_t after = progress_in(ping_heartbeat(context, connection));
    expect(after >= before, "the heartbeat's progress went back from " + std::to_string(before) + " to " + std::to_string(after) +
                                "; it counts the main thread's work and never decreases (SPEC.md §9.1)");
    before = after;
  }
}

void heartbeat_refuses_other_types(Context& context) {
  protocol::Connection connection(context.zmq_context(), announced_endpoint(context), "the heartbeat", protocol::Limits{}, context.server_key());
  expect_error(ping_heartbeat(context, connection, protocol::type::query), {"UNKNOWN_TYPE"});
}

}  // namespace

std::vector<Check> heartbeat_checks() {
  using M = Milestone;
  constexpr int since = heartbeat::kSinceMinor;
  return {
      {"heartbeat.announced", "hello_ok names a heartbeat_endpoint on the loopback (1.6)", M::greeted, M::none, false, heartbeat_is_announced,
       since},
      {"heartbeat.pong", "the heartbeat answers ping with pong counting the requests the main socket answered (1.6)", M::greeted, M::none,
       true, heartbeat_answers_ping, since},
      {"heartbeat.progress", "every pong carries progress, an integer that never decreases (1.8)", M::greeted, M::none, true,
       heartbeat_reports_progress, heartbeat::kProgressSinceMinor},
      {"heartbeat.other_types_refused", "the heartbeat answers any other request with UNKNOWN_TYPE (1.6)", M::greeted, M::none, true,
       heartbeat_refuses_other_types, since},
  };
}

}  // namespace dfc::conformance
