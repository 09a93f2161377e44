// SPEC.md §4.2, §5.1: ordering in the greeted state, a rejected section
// leaving the server greeted, the scenario hash and the configured info.
#include <algorithm>
#include <cmath>

#include "check.hpp"
#include "context.hpp"
#include "dfc/common/version.hpp"
#include "dfc/protocol/monitor_units.hpp"
#include "expectations.hpp"
#include "requests.hpp"

namespace dfc::conformance {

namespace protocol = dfc::protocol;

namespace {

void advance_before_configure_is_out_of_order(Context& context) {
  expect_error(context.request(advance_request(0, 1, context.dt)), {"OUT_OF_ORDER"});
}

void query_before_configure_is_out_of_order(Context& context) {
  expect_error(context.request(protocol::type::query), {"OUT_OF_ORDER"});
}

void invalid_json_section_is_bad_config(Context& context) {
  expect_error(context.request(protocol::type::configure, {{"section_json", "{\"unterminated\": "}}), {"BAD_CONFIG"});
}

void section_json_must_be_text(Context& context) {
  // section_json is JSON *text* so that both sides hash the same bytes; an
  // object in its place is the wrong type of a required field.
  expect_error(context.request(protocol::type::configure, {{"section_json", nlohmann::json::object()}}), {"BAD_MESSAGE", "BAD_CONFIG"});
}

bool positive_number(const nlohmann::json& value) {
  return value.is_number() && std::isfinite(value.get<double>()) && value.get<double>() > 0.0;
}

// A server whose role is chosen by its section (fdm_server: provider or
// driven) announces every capability it might serve in hello_ok, and may
// list the ones this configured session serves in info.capabilities. Only
// a subset makes sense; later checks then follow the narrowed list.
void narrow_capabilities(Context& context, const nlohmann::json& info) {
  const auto listed = info.find("capabilities");
  if (listed == info.end()) return;
  expect(listed->is_array(), "configured.info.capabilities must be an array of strings, got " + listed->dump());
  const auto announced = context.hello_reply->body.value("capabilities", nlohmann::json::array());
  for (const auto& c : *listed)
    expect(c.is_string() && std::find(announced.begin(), announced.end(), c) != announced.end(),
           "configured.info.capabilities lists " + c.dump() + ", which hello_ok did not announce");
  const auto serves = [&](const char* name) { return std::find(listed->begin(), listed->end(), name) != listed->end(); };
  context.provides_interface = serves(protocol::capability::provides_interface);
  context.accepts_interface = serves(protocol::capability::accepts_interface);
  context.snapshot = serves(protocol::capability::snapshot);
  context.checkpoint = serves(protocol::capability::checkpoint);
}

void configure_is_accepted_with_hash(Context& context) {
  const std::string& section = context.options().section_json;
  const protocol::Message reply = context.request(protocol::type::configure, {{"section_json", section}});
  expect_type(reply, protocol::type::configured);
  const std::string expected = fnv1a64_hex(section);
  const std::string reported = reply.body.value("scenario_hash", "(none)");
  expect(reported == expected, "scenario_hash is '" + reported + "', but FNV-1a 64 of the " + std::to_string(section.size()) +
                                   " bytes sent is '" + expected + "'");
  expect(reply.body.contains("info") && reply.body["info"].is_object(), "configured needs an object 'info'");
  const nlohmann::json& info = reply.body["info"];
  expect(info.contains("dt_suggested") && positive_number(info["dt_suggested"]),
         "configured.info.dt_suggested must be a positive number of seconds, got " + info.value("dt_suggested", nlohmann::json()).dump());
  expect(info.contains("dt_max") && (info["dt_max"].is_null() || positive_number(info["dt_max"])),
         "configured.info.dt_max must be a positive number or null, got " + info.value("dt_max", nlohmann::json()).dump());
  narrow_capabilities(context, info);
  context.configured_info = info;
  context.monitor_units = info.value(protocol::monitor_units_key, nlohmann::json());
  expect(context.monitor_units.is_null() || context.monitor_units.is_object(),
         "configured.info.monitor_units must be an object {monitor: unit}, got " + context.monitor_units.dump().substr(0, 200));
  context.dt = info["dt_suggested"].get<double>();
  if (info["dt_max"].is_number()) {
    context.dt_max = info["dt_max"].get<double>();
    context.dt = std::min(context.dt, *context.dt_max);
  }
  context.step = 0;
}

void second_configure_is_out_of_order(Context& context) {
  expect_error(context.request(protocol::type::configure, {{"section_json", context.options().section_json}}), {"OUT_OF_ORDER"});
}

}  // namespace

std::vector<Check> configure_checks() {
  using M = Milestone;
  return {
      {"greeted.advance_refused", "advance before configure gets OUT_OF_ORDER", M::greeted, M::none, true,
       advance_before_configure_is_out_of_order},
      {"greeted.query_refused", "query before configure gets OUT_OF_ORDER", M::greeted, M::none, true, query_before_configure_is_out_of_order},
      {"configure.invalid_json", "section_json that is not JSON gets BAD_CONFIG (the server stays greeted)", M::greeted, M::none, true,
       invalid_json_section_is_bad_config},
      {"configure.section_not_text", "section_json as an object instead of text gets BAD_MESSAGE or BAD_CONFIG", M::greeted, M::none, true,
       section_json_must_be_text},
      {"configure.accepted", "the --config section gets configured with its FNV-1a hash, dt_suggested and dt_max", M::greeted,
       M::configured, true, configure_is_accepted_with_hash},
      {"configured.second_configure_refused", "a second configure gets OUT_OF_ORDER", M::configured, M::none, true,
       second_configure_is_out_of_order},
  };
}

}  // namespace dfc::conformance
