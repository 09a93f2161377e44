#include "fresh_server.hpp"

#include <string>

#include "context.hpp"
#include "expectations.hpp"
#include "requests.hpp"

namespace dfc::conformance {

namespace protocol = dfc::protocol;

namespace {

/// Sends `request` and throws CheckFailure unless the reply is `expected`.
protocol::Message expect_reply(Context& context, protocol::Message request, std::string_view expected) {
  const std::string what = request.type;
  try {
    const protocol::Message reply = context.request(std::move(request));
    expect_type(reply, expected);
    return reply;
  } catch (const std::exception& e) {
    throw CheckFailure("a fresh server could not be brought back: its '" + what + "' failed: " + e.what());
  }
}

protocol::Message plain(std::string_view type, nlohmann::json body = nlohmann::json::object()) {
  protocol::Message message;
  message.type = std::string(type);
  message.body = std::move(body);
  return message;
}

}  // namespace

void bring_fresh_server_to(Context& context, Milestone milestone) {
  if (context.server_started()) {  // keep what the failed process said, for the report
    context.server().kill();
    context.replaced_stderr_tail = context.server().stderr_tail(kStderrTailLines);
  }
  context.start_server();
  context.unavailable.reset();
  context.set_exit_expected(false);
  context.step = 0;
  if (milestone < Milestone::greeted) return;
  context.hello_reply = expect_reply(context, hello_request(protocol::version_string()), protocol::type::hello_ok);
  if (milestone < Milestone::configured) return;
  expect_reply(context, plain(protocol::type::configure, {{"section_json", context.options().section_json}}), protocol::type::configured);
  // The interface exchanges that passed the first time; advance needs them.
  if (context.provides_interface && context.provided_nodes)
    expect_reply(context, plain(protocol::type::get_interface), protocol::type::interface);
  if (context.accepts_interface && context.accepted_nodes) expect_reply(context, test_mesh_request(), protocol::type::ok);
  if (milestone < Milestone::stepped) return;
  expect_reply(context, advance_with_zero_inputs(context, 0, 1, context.dt), protocol::type::advanced);
  context.step = 1;
}

}  // namespace dfc::conformance
