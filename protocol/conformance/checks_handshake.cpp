// SPEC.md §2, §4.1, §5.1: the listening line, ping in any state, version
// refusal leaving the server fresh, hello_ok's fields, and hello only once.
#include <regex>

#include "check.hpp"
#include "context.hpp"
#include "expectations.hpp"
#include "requests.hpp"

namespace dfc::conformance {

namespace protocol = dfc::protocol;

namespace {

bool has_capability(const nlohmann::json& capabilities, std::string_view name) {
  if (!capabilities.is_array()) return false;
  for (const auto& c : capabilities)
    if (c.is_string() && c.get<std::string>() == name) return true;
  return false;
}

void server_prints_listening_line(Context& context) { context.start_server(); }

void ping_before_hello(Context& context) {
  const protocol::Message reply = context.request(protocol::type::ping);
  expect_type(reply, protocol::type::pong);
  expect(reply.reply_to.has_value(), "'pong' lacks reply_to (the seq of the ping)");
}

void configure_before_hello_is_out_of_order(Context& context) {
  expect_error(context.request(protocol::type::configure, {{"section_json", context.options().section_json}}), {"OUT_OF_ORDER"});
}

void major_version_mismatch_is_refused(Context& context) {
  const protocol::Message reply = context.request(hello_request("99.0"));
  expect_error(reply, {"VERSION_MISMATCH"});
  const std::string message = reply.body["message"].get<std::string>();
  // Both versions must be named: the client's 99.0 and the server's own 1.x.
  expect(message.find("99.0") != std::string::npos, "the VERSION_MISMATCH message does not name the client's version 99.0: \"" + message + "\"");
  const std::regex own_version("(^|[^0-9])" + std::to_string(protocol::kVersionMajor) + "\\.[0-9]+");
  expect(std::regex_search(message, own_version), "the VERSION_MISMATCH message does not name the server's version: \"" + message + "\"");
}

void hello_after_refusal_is_accepted(Context& context) {
  const protocol::Message reply = context.request(hello_request(protocol::version_string()));
  expect_type(reply, protocol::type::hello_ok);
  context.hello_reply = reply;
  if (const auto version = protocol::parse_version(reply.body.value("protocol_version", std::string())))
    context.declared_minor = version->second;
  // Learn what later checks need; hello_ok's field check reports malformed values.
  const auto& body = reply.body;
  const auto capabilities = body.value("capabilities", nlohmann::json::array());
  context.provides_interface = has_capability(capabilities, protocol::capability::provides_interface);
  context.accepts_interface = has_capability(capabilities, protocol::capability::accepts_interface);
  context.snapshot = has_capability(capabilities, protocol::capability::snapshot);
  context.checkpoint = has_capability(capabilities, protocol::capability::checkpoint);
  const auto limits = body.value("limits", nlohmann::json::object());
  const auto limit = [&](const char* key, std::size_t fallback) {
    const auto it = limits.find(key);
    return it != limits.end() && it->is_number_unsigned() && it->get<std::uint64_t>() > 0 ? it->get<std::size_t>() : fallback;
  };
  context.limits.max_header_bytes = limit("max_header_bytes", context.limits.max_header_bytes);
  context.limits.max_array_bytes = limit("max_array_bytes", context.limits.max_array_bytes);
  context.limits.max_arrays = limit("max_arrays", context.limits.max_arrays);
}

void expect_string(const nlohmann::json& object, const char* key, const std::string& where) {
  const auto it = object.find(key);
  expect(it != object.end() && it->is_string() && !it->get<std::string>().empty(), where + " needs a non-empty string '" + key + "'");
}

void hello_ok_has_required_fields(Context& context) {
  const nlohmann::json& body = context.hello_reply->body;
  expect_string(body, "protocol_version", "hello_ok");
  const auto version = protocol::parse_version(body["protocol_version"].get<std::string>());
  expect(version && version->first == protocol::kVersionMajor,
         "hello_ok.protocol_version '" + body["protocol_version"].get<std::string>() + "' is not " + std::to_string(protocol::kVersionMajor) + ".x");
  expect(body.contains("solver") && body["solver"].is_object(), "hello_ok needs an object 'solver' {name, version}");
  expect_string(body["solver"], "name", "hello_ok.solver");
  expect_string(body["solver"], "version", "hello_ok.solver");
  expect_string(body, "role", "hello_ok");
  const std::string role = body["role"].get<std::string>();
  expect(role == "dem" || role == "continuum", "hello_ok.role is '" + role + "', expected 'dem' or 'continuum'");
  expect(body.contains("capabilities") && body["capabilities"].is_array(), "hello_ok needs an array 'capabilities'");
  for (const auto& c : body["capabilities"]) expect(c.is_string(), "hello_ok.capabilities holds a non-string " + c.dump());
  expect(body.contains("limits") && body["limits"].is_object(), "hello_ok needs an object 'limits'");
  for (const char* key : {"max_header_bytes", "max_array_bytes", "max_arrays"}) {
    const auto it = body["limits"].find(key);
    expect(it != body["limits"].end() && it->is_number_unsigned() && it->get<std::uint64_t>() > 0,
           std::string("hello_ok.limits.") + key + " must be a positive integer");
  }
}

void second_hello_is_out_of_order(Context& context) {
  expect_error(context.request(hello_request(protocol::version_string())), {"OUT_OF_ORDER"});
}

}  // namespace

std::vector<Check> handshake_checks() {
  using M = Milestone;
  return {
      {"server.listening", "COMMAND --bind tcp://127.0.0.1:* prints 'DFC-LISTENING tcp://127.0.0.1:<port>'", M::none, M::listening, false,
       server_prints_listening_line},
      {"fresh.ping", "ping before hello gets pong", M::listening, M::none, true, ping_before_hello},
      {"fresh.configure_refused", "configure before hello gets OUT_OF_ORDER", M::listening, M::none, true,
       configure_before_hello_is_out_of_order},
      {"fresh.version_mismatch", "hello speaking 99.0 gets VERSION_MISMATCH naming both versions", M::listening, M::none, true,
       major_version_mismatch_is_refused},
      {"handshake.hello", "a correct hello after the refusal gets hello_ok (the server stayed fresh)", M::listening, M::greeted, true,
       hello_after_refusal_is_accepted},
      {"handshake.hello_ok_fields", "hello_ok has protocol_version, solver, role, capabilities and limits", M::greeted, M::none, false,
       hello_ok_has_required_fields},
      {"greeted.second_hello_refused", "a second hello gets OUT_OF_ORDER", M::greeted, M::none, true, second_hello_is_out_of_order},
  };
}

}  // namespace dfc::conformance
