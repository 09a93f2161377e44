// SPEC.md §2.1 (1.7): a server started with DFC_KEY_FILE makes every socket
// it binds, the main one and the heartbeat, a CURVE server with that key and
// says so before DFC-LISTENING; a stranger, a client without the key or with
// another key, gets no answer, and the run goes on for the client that holds
// it. For servers that declare 1.7 or later (Check::since_minor).
#include <algorithm>
#include <future>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "announced_heartbeat.hpp"
#include "check.hpp"
#include "context.hpp"
#include "dfc/protocol/authentication.hpp"
#include "expectations.hpp"

namespace dfc::conformance {

namespace protocol = dfc::protocol;
namespace authentication = dfc::protocol::authentication;

namespace {

// An authorised client is answered within milliseconds; a second without an
// answer shows the stranger was refused, without the checker waiting a full
// --timeout for each stranger.
constexpr std::chrono::milliseconds kStrangerWait{1000};

void require_authentication(const Context& context) {
  if (!context.authenticated())
    throw NotApplicable("the server does not authenticate (see authentication.announced)");
}

/// The strangers: a client of the NULL mechanism (no key) and a CURVE client
/// that knows another server key than the run's.
struct Stranger {
  std::string name;
  std::optional<std::string> server_key;
};

std::vector<Stranger> strangers() {
  return {{"a client without a key", std::nullopt}, {"a client with another key", authentication::generate_key_pair().public_key}};
}

/// The type of the reply `stranger` gets from `endpoint` to a ping, or nullopt: none.
std::optional<std::string> stranger_reply(zmq::context_t& zmq_context, const std::string& endpoint, const Stranger& stranger,
                                          std::chrono::milliseconds wait) {
  protocol::Connection connection(zmq_context, endpoint, stranger.name, protocol::Limits{}, stranger.server_key);
  protocol::Message ping;
  ping.type = std::string(protocol::type::ping);
  try {
    return connection.request_raw(std::move(ping), wait).type;
  } catch (const protocol::TimeoutError&) {
    return std::nullopt;  // refused: what the rule asks
  }
}

/// Throws CheckFailure if any stranger gets an answer from `endpoint` (`what`
/// names it). The strangers wait side by side, each on a socket of its own
/// thread, so that the check takes one wait, not one per stranger.
void expect_strangers_unanswered(Context& context, const std::string& endpoint, const std::string& what) {
  const auto wait = std::min(kStrangerWait, context.timeout());
  std::vector<std::pair<Stranger, std::future<std::optional<std::string>>>> attempts;
  for (auto& stranger : strangers())
    attempts.emplace_back(stranger, std::async(std::launch::async, stranger_reply, std::ref(context.zmq_context()), endpoint, stranger, wait));
  for (auto& [stranger, attempt] : attempts)
    if (const auto reply = attempt.get())
      throw CheckFailure(stranger.name + " was answered by " + what + " with '" + *reply +
                         "': started with DFC_KEY_FILE, every socket of a 1.7 server must refuse a peer that does not hold the key (SPEC.md §2.1)");
}

void expect_pong(Context& context, const std::string& endpoint, const std::string& what) {
  protocol::Connection connection(context.zmq_context(), endpoint, what, protocol::Limits{}, context.server_key());
  protocol::Message ping;
  ping.type = std::string(protocol::type::ping);
  try {
    expect_type(connection.request_raw(std::move(ping), context.timeout()), protocol::type::pong);
  } catch (const protocol::TimeoutError& e) {
    throw CheckFailure("a new client holding the key got no answer from " + what + ": " + e.what());
  }
}

void authentication_is_announced(Context& context) {
  expect(context.authenticated(), "started with " + std::string(authentication::kKeyFileVariable) +
                                      " naming a key file, a 1.7 server must use it on every socket and print '" +
                                      std::string(authentication::kAnnouncement) +
                                      "' before its DFC-LISTENING line (SPEC.md §2.1); it printed none, so any process on the host can talk to it");
}

void main_socket_refuses_strangers(Context& context) {
  require_authentication(context);
  expect_strangers_unanswered(context, context.endpoint(), "the main socket");
}

void heartbeat_refuses_strangers(Context& context) {
  require_authentication(context);
  expect_strangers_unanswered(context, announced_endpoint(context), "the heartbeat");
}

void key_holders_are_answered(Context& context) {
  require_authentication(context);
  // A client key pair the server has never seen: the server key alone is the credential.
  expect_pong(context, context.endpoint(), "the main socket");
  expect_pong(context, announced_endpoint(context), "the heartbeat");
}

}  // namespace

std::vector<Check> authentication_checks() {
  using M = Milestone;
  constexpr int since = authentication::kSinceMinor;
  return {
      {"authentication.announced", "started with DFC_KEY_FILE, the server prints 'DFC-AUTHENTICATION curve' before DFC-LISTENING (1.7)",
       M::greeted, M::none, false, authentication_is_announced, since},
      {"authentication.stranger_refused", "the main socket answers no client without the key or with another key (1.7)", M::greeted,
       M::none, true, main_socket_refuses_strangers, since},
      {"authentication.heartbeat_stranger_refused", "the heartbeat answers no client without the key or with another key (1.7)",
       M::greeted, M::none, true, heartbeat_refuses_strangers, since},
      {"authentication.key_holder_answered", "a new client holding the key is answered on both sockets (1.7)", M::greeted, M::none, true,
       key_holders_are_answered, since},
  };
}

}  // namespace dfc::conformance
